#include "analysis/learn/prefix_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "analysis/learn/cross_validation.hpp"
#include "analysis/learn/parallel_for.hpp"
#include "analysis/series/model_rule.hpp"
#include "analysis/series/series_table.hpp"

namespace rollsense::learn {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// The recordings of `records`, loaded on `threads` threads; the first error names the file.
Result<std::vector<TrialData>> load_trials(const DatasetReader& ds, const std::filesystem::path& dataset_dir,
                                           const std::vector<TrialRecord>& records, unsigned threads) {
    std::vector<TrialData> data(records.size());
    std::vector<Status> errors(records.size());
    parallel_for(records.size(), threads, [&](std::size_t i) {
        auto d = ds.load(records[i]);
        if (!d) errors[i] = Status(d.error()).with_context((dataset_dir / records[i].file).string());
        else data[i] = std::move(d).value();
    });
    for (const auto& st : errors)
        if (!st) return st.error();
    return data;
}

// A dataset with the channels a series classifier reads, and their column indices.
struct SeriesDataset {
    DatasetReader reader;
    std::vector<std::string> channels;
    std::vector<std::size_t> channel_idx;
};
Result<SeriesDataset> open_series_dataset(const std::filesystem::path& dataset_dir) {
    auto ds = DatasetReader::open(dataset_dir);
    if (!ds) return ds.error();
    auto channels = series_channels(ds->info(), dataset_dir.string());
    if (!channels) return channels.error();
    auto channel_idx = series::channel_indices(ds->info(), *channels);
    if (!channel_idx) return channel_idx.error();
    return SeriesDataset{std::move(*ds), std::move(*channels), std::move(*channel_idx)};
}

Status check_fractions(const std::vector<double>& fractions) {
    if (fractions.empty()) return Error{ErrorCode::invalid_argument, "prefixes: no fraction given"};
    for (double f : fractions)
        if (!(f > 0.0 && f <= 1.0))
            return Error{ErrorCode::invalid_argument,
                         "prefixes: fraction " + std::to_string(f) + " is outside (0, 1] (1 = the whole roll)"};
    return {};
}

}  // namespace

std::size_t prefix_samples(double fraction, const std::optional<series::ContactClock>& clock, double units,
                           std::size_t samples) {
    if (fraction >= 1.0) return samples;
    if (!clock) return 0;
    // The fewest samples whose clock_progress reaches `fraction`, but never
    // before the sample that showed the clock (before it no cut can be placed).
    const double cut = clock->zero + fraction * units * clock->unit;
    const std::size_t keep = std::max(clock->known_at, static_cast<std::size_t>(std::ceil(cut))) + 1;
    return std::min(keep, samples);
}

PrefixCuts prefix_cuts(const std::vector<TrialRecord>& records, const std::vector<TrialData>& data,
                       std::span<const std::size_t> channels, const series::SeriesSettings& settings) {
    PrefixCuts out;
    out.clock.resize(records.size());
    series::SeriesSettings whole = settings;
    whole.prefix = 0;
    std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by_speed;
    std::vector<double> units;
    for (std::size_t i = 0; i < records.size(); ++i) {
        out.clock[i] = series::contact_clock(data[i], channels, whole);
        auto& [samples, seconds] = by_speed[records[i].info.speed];
        const auto& c = out.clock[i];
        if (!c) continue;  // no clock to count the roll on
        const auto zero = static_cast<std::size_t>(std::ceil(c->zero));
        samples.push_back(static_cast<double>(data[i].samples() - zero));
        seconds.push_back(data[i].time.size() > zero ? data[i].time.back() - data[i].time[zero] : 0.0);
        units.push_back(series::clock_progress(*c, 1.0, data[i].samples()));
    }
    out.units = median(units);
    for (auto& [speed, v] : by_speed)
        out.nominal.push_back({speed, median(v.first), median(v.second), v.first.size()});
    // Numeric speed labels in ascending order ("10" < "15" < "20" < "100").
    std::stable_sort(out.nominal.begin(), out.nominal.end(), [](const NominalLength& a, const NominalLength& b) {
        return a.speed.size() != b.speed.size() ? a.speed.size() < b.speed.size() : a.speed < b.speed;
    });
    return out;
}

std::size_t PrefixCuts::keep(std::size_t trial, double fraction, std::size_t samples) const {
    return prefix_samples(fraction, clock[trial], units, samples);
}

std::size_t PrefixCuts::series_prefix(std::size_t trial, double fraction, std::size_t samples) const {
    return fraction >= 1.0 ? 0 : std::max<std::size_t>(keep(trial, fraction, samples), 1);
}

Result<PrefixCurves> prefix_curves(const std::filesystem::path& dataset_dir, const Evaluation& ev,
                                   const std::vector<PreparedClassifier>& classifiers,
                                   const features::FeatureSettings& feature_settings, const InputOptions& inputs,
                                   const PrefixOptions& options) {
    if (auto st = check_fractions(options.fractions); !st) return st.error();
    if (classifiers.size() != ev.classifiers.size())
        return Error{ErrorCode::invalid_argument, "prefixes: the classifiers are not the evaluation's"};
    if (auto st = check_input_holds_trials(dataset_dir, {}, true); !st) return st.error();
    auto opened = open_series_dataset(dataset_dir);
    if (!opened) return opened.error();
    const DatasetReader& ds = opened->reader;
    const std::vector<std::string>& channels = opened->channels;
    const std::vector<std::size_t>& channel_idx = opened->channel_idx;

    // The evaluation's trials, loaded once.
    std::map<std::string, const TrialRecord*> record_of;
    for (const auto& r : ds.trials()) record_of[r.info.id] = &r;
    const std::size_t n = ev.trial_ids.size();
    std::vector<TrialRecord> records;
    for (const auto& id : ev.trial_ids) {
        const auto it = record_of.find(id);
        if (it == record_of.end())
            return Error{ErrorCode::not_found, "prefixes: trial '" + id + "' is not in " + dataset_dir.string() +
                                                   "/manifest.csv (evaluation and dataset out of step?)"};
        records.push_back(*it->second);
    }
    auto loaded = load_trials(ds, dataset_dir, records, options.threads);
    if (!loaded) return loaded.error();
    const std::vector<TrialData>& data = *loaded;

    PrefixCurves out;
    out.fractions = options.fractions;
    out.folds = ev.plan.folds;
    out.repeats = std::clamp(options.repeats, 1, static_cast<int>(ev.plan.repeats()));
    const PrefixCuts cuts = prefix_cuts(records, data, channel_idx, inputs.series);
    out.nominal = cuts.nominal;
    out.units = cuts.units;
    std::map<std::string, const NominalLength*> nominal_of;
    for (const auto& nl : out.nominal) nominal_of[nl.speed] = &nl;

    const bool need_features = std::any_of(classifiers.begin(), classifiers.end(),
                                           [](const auto& c) { return c.input == ClassifierInput::features; });
    const bool need_series = std::any_of(classifiers.begin(), classifiers.end(),
                                         [](const auto& c) { return c.input == ClassifierInput::series; });
    for (std::size_t c = 0; c < classifiers.size(); ++c) {
        PrefixCurve curve;
        curve.classifier = ev.classifiers[c].name;
        curve.input = classifiers[c].input == ClassifierInput::series ? "series" : "features";
        for (const auto& nl : out.nominal) curve.by_speed.push_back({nl.speed, {}});
        out.classifiers.push_back(std::move(curve));
    }

    for (double f : options.fractions) {
        if (options.progress) {
            char buf[96];
            std::snprintf(buf, sizeof buf, "prefixes: %.0f %% of the nominal roll on the contact's clock", 100.0 * f);
            options.progress(buf);
        }
        // Each trial's prefix through both input steps (the same rules as the full trials).
        FeatureTable ftab, stab;
        std::vector<char> f_ok(n, 0), s_ok(n, 0);
        std::vector<std::array<double, features::kFeatureCount>> fvals(n);
        std::vector<std::vector<double>> svals(n);
        std::vector<Status> errors(n);
        parallel_for(n, options.threads, [&](std::size_t i) {
            const TrialData& d = data[i];
            const std::size_t keep = cuts.keep(i, f, d.samples());
            if (need_features && keep > 0) {
                features::FeatureExtractor extractor(feature_settings);
                std::array<std::span<const double>, features::kChannels> ch;
                for (std::size_t k = 0; k < features::kChannels; ++k)
                    ch[k] = std::span<const double>(d.channels[channel_idx[k]]).first(keep);
                const std::span<const double> time =
                    d.time.size() >= keep ? std::span<const double>(d.time).first(keep) : std::span<const double>{};
                auto tf = extractor.extract(std::span<const std::span<const double>>(ch), time);
                if (!tf) {
                    errors[i] = Status(tf.error()).with_context("trial " + records[i].info.id);
                    return;
                }
                if (tf->clean) {
                    f_ok[i] = 1;
                    fvals[i] = tf->values;
                }
            }
            if (need_series) {
                series::SeriesSettings s = inputs.series;
                s.prefix = cuts.series_prefix(i, f, d.samples());
                auto p = series::prepare_series(d, channel_idx, s);
                if (!p) {
                    errors[i] = Status(p.error()).with_context("trial " + records[i].info.id);
                    return;
                }
                if (p->ok) {
                    s_ok[i] = 1;
                    svals[i] = std::move(p->values);
                }
            }
        });
        for (const auto& st : errors)
            if (!st) return st.error();
        // Full tables (every trial; rows without a decision hold zeros and are never used).
        ftab.feature_names.assign(features::feature_names().begin(), features::feature_names().end());
        stab.channel_names = channels;
        series::describe_series(stab, inputs.series);
        for (auto* t : {&ftab, &stab}) {
            t->class_names = ev.classes;
            t->y = ev.truth;
            t->rows = n;
        }
        if (need_features)
            for (std::size_t i = 0; i < n; ++i) ftab.x.insert(ftab.x.end(), fvals[i].begin(), fvals[i].end());
        if (need_series)
            for (std::size_t i = 0; i < n; ++i) {
                if (s_ok[i]) stab.x.insert(stab.x.end(), svals[i].begin(), svals[i].end());
                else stab.x.resize(stab.x.size() + stab.cols(), 0.0);
            }

        for (std::size_t c = 0; c < classifiers.size(); ++c) {
            const bool series_kind = classifiers[c].input == ClassifierInput::series;
            const FeatureTable& table = series_kind ? stab : ftab;
            const std::vector<char>& ok = series_kind ? s_ok : f_ok;
            PrefixPoint all{f};
            std::map<std::string, PrefixPoint> per_speed;
            for (int r = 0; r < out.repeats; ++r) {
                const auto& assignment = ev.plan.assignment[static_cast<std::size_t>(r)];
                for (int k = 0; k < ev.plan.folds; ++k) {
                    std::vector<std::size_t> train, test_ok;
                    std::vector<std::size_t> test_all;
                    for (std::size_t i = 0; i < n; ++i) {
                        if (assignment[i] == k) {
                            test_all.push_back(i);
                            if (ok[i]) test_ok.push_back(i);
                        } else if (ok[i]) {
                            train.push_back(i);
                        }
                    }
                    std::vector<int> predicted(n, -1);
                    std::set<int> train_classes;
                    for (std::size_t i : train) train_classes.insert(table.y[i]);
                    if (!test_ok.empty() && train_classes.size() >= 2) {
                        auto model = train_classifier(subset(table, train), classifiers[c].factory,
                                                      classifiers[c].spec.params);
                        if (!model)
                            return Status(model.error()).with_context("prefixes at " + std::to_string(f) +
                                                                      ", classifier '" + ev.classifiers[c].name + "'");
                        auto labels = predict_labels(**model, table, test_ok);
                        if (!labels) return labels.error();
                        for (std::size_t j = 0; j < test_ok.size(); ++j) predicted[test_ok[j]] = (*labels)[j];
                    }
                    for (std::size_t i : test_all) {
                        auto& sp = per_speed[records[i].info.speed];
                        for (auto* p : {&all, &sp}) {
                            ++p->total;
                            if (!ok[i]) ++p->no_decision;
                            else if (predicted[i] == table.y[i]) ++p->correct;
                        }
                    }
                }
            }
            auto& curve = out.classifiers[c];
            curve.points.push_back(all);
            for (auto& sc : curve.by_speed) {
                PrefixPoint p = per_speed[sc.speed];
                p.fraction = f;
                p.seconds = f * nominal_of.at(sc.speed)->seconds;
                sc.points.push_back(p);
            }
        }
    }
    // Where each classifier reaches 95 % of its accuracy at the largest fraction.
    const std::size_t last =
        static_cast<std::size_t>(std::max_element(out.fractions.begin(), out.fractions.end()) - out.fractions.begin());
    for (auto& curve : out.classifiers) {
        const double full = curve.points[last].accuracy();
        std::optional<double> best;
        for (const auto& p : curve.points)
            if (p.accuracy() >= 0.95 * full && (!best || p.fraction < *best)) best = p.fraction;
        curve.fraction_95 = best;
    }
    return out;
}

Result<PrefixModels> train_prefix_models(const std::filesystem::path& dataset_dir,
                                         const PreparedClassifier& classifier, const InputOptions& inputs,
                                         const std::vector<double>& fractions) {
    if (auto st = check_fractions(fractions); !st) return st.error();
    if (classifier.input != ClassifierInput::series)
        return Error{ErrorCode::unsupported, "prefix models: classifier '" + classifier.spec.name +
                                                 "' takes features; prefix models are implemented for series "
                                                 "classifiers (e.g. minirocket)"};
    auto opened = open_series_dataset(dataset_dir);
    if (!opened) return opened.error();
    const DatasetReader& ds = opened->reader;
    const std::vector<std::string>& channels = opened->channels;
    const std::vector<std::size_t>& channel_idx = opened->channel_idx;
    const std::vector<TrialRecord> records(ds.trials().begin(), ds.trials().end());
    if (records.empty()) return Error{ErrorCode::invalid_argument, dataset_dir.string() + ": no trials to train on"};
    auto loaded = load_trials(ds, dataset_dir, records, inputs.threads);
    if (!loaded) return loaded.error();
    const std::vector<TrialData>& data = *loaded;

    PrefixModels out;
    const PrefixCuts cuts = prefix_cuts(records, data, channel_idx, inputs.series);
    out.nominal = cuts.nominal;
    out.units = cuts.units;
    std::set<std::string> objects;
    for (const auto& r : records) objects.insert(r.info.object);
    const std::vector<std::string> class_names(objects.begin(), objects.end());

    for (double f : fractions) {
        std::vector<std::vector<double>> values(records.size());
        std::vector<Status> errors(records.size());
        parallel_for(records.size(), inputs.threads, [&](std::size_t i) {
            series::SeriesSettings s = inputs.series;
            s.prefix = cuts.series_prefix(i, f, data[i].samples());
            auto p = series::prepare_series(data[i], channel_idx, s);
            if (!p) errors[i] = Status(p.error()).with_context("trial " + records[i].info.id);
            else if (p->ok) values[i] = std::move(p->values);
        });
        for (const auto& st : errors)
            if (!st) return st.error();
        FeatureTable table;
        table.channel_names = channels;
        series::describe_series(table, inputs.series);  // the models are saved: their rule goes with them
        table.class_names = class_names;
        PrefixModel pm;
        pm.fraction = f;
        std::set<int> classes_seen;
        for (std::size_t i = 0; i < records.size(); ++i) {
            if (values[i].empty()) {
                ++pm.refused;
                continue;
            }
            const int y = static_cast<int>(
                std::lower_bound(class_names.begin(), class_names.end(), records[i].info.object) - class_names.begin());
            table.x.insert(table.x.end(), values[i].begin(), values[i].end());
            table.y.push_back(y);
            classes_seen.insert(y);
            ++table.rows;
        }
        pm.trained = table.rows;
        if (classes_seen.size() < 2) {  // too early in the roll to tell objects apart: no model
            if (f >= 1.0)
                return Error{ErrorCode::invalid_argument,
                             "prefix models: the series rule accepts whole trials of fewer than two objects in " +
                                 dataset_dir.string() + "; record more objects"};
            out.models.push_back(std::move(pm));
            continue;
        }
        auto model = train_classifier(table, classifier.factory, classifier.spec.params);
        if (!model) return Status(model.error()).with_context("prefix model at " + std::to_string(f));
        pm.model = std::move(model).value();
        out.models.push_back(std::move(pm));
    }
    return out;
}

std::string format_prefix_curves(const PrefixCurves& pc) {
    std::string out;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "\nidentification before the roll ends (%d x %d-fold on the same partitions; prefix = the recording up "
                  "to a fraction of the nominal roll on the contact's own clock; no decision counts as wrong):\n",
                  pc.repeats, pc.folds);
    out += buf;
    std::snprintf(buf, sizeof buf, "  nominal roll %.2f clock units (median over the trials); after the clock's zero:",
                  pc.units);
    out += buf;
    for (const auto& nl : pc.nominal) {
        std::snprintf(buf, sizeof buf, " speed %s %.0f samples / %.2f s;", nl.speed.c_str(), nl.samples, nl.seconds);
        out += buf;
    }
    out.back() = '\n';
    out += "  ";
    out += kPrefixTimingNote;
    out += "\n";
    for (const auto& c : pc.classifiers) {
        out += "  " + c.classifier + " (" + c.input + "):\n    fraction ";
        for (const auto& p : c.points) {
            std::snprintf(buf, sizeof buf, " %5.0f%%", 100.0 * p.fraction);
            out += buf;
        }
        out += "\n    accuracy ";
        for (const auto& p : c.points) {
            std::snprintf(buf, sizeof buf, " %5.1f%%", 100.0 * p.accuracy());
            out += buf;
        }
        out += "\n    no decis.";
        for (const auto& p : c.points) {
            std::snprintf(buf, sizeof buf, " %5.1f%%",
                          p.total ? 100.0 * static_cast<double>(p.no_decision) / static_cast<double>(p.total) : 0.0);
            out += buf;
        }
        out += "\n";
        for (const auto& s : c.by_speed) {
            std::snprintf(buf, sizeof buf, "    speed %-4s", s.speed.c_str());
            out += buf;
            for (const auto& p : s.points) {
                std::snprintf(buf, sizeof buf, " %5.1f%%", 100.0 * p.accuracy());
                out += buf;
            }
            out += "\n";
        }
        if (c.fraction_95) {
            std::snprintf(buf, sizeof buf, "    reaches 95 %% of its full-roll accuracy at %.0f %% of the roll\n",
                          100.0 * *c.fraction_95);
            out += buf;
        }
    }
    return out;
}

}  // namespace rollsense::learn
