// rollsense predict MODEL (TRIAL.csv | DATASET): classify recordings with a
// saved model, computing each trial's input with the code training used, and
// say when the input is unlike what the model was trained on.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "cli/paths.hpp"
#include "analysis/learn/json_writer.hpp"
#include "analysis/learn/model_header.hpp"
#include "analysis/learn/plugin_factory.hpp"
#include "analysis/series/model_rule.hpp"
#include "analysis/series/series_table.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/dataset_files.hpp"
#include "rollsense/features.hpp"

namespace rollsense::cli {

features::FeatureSettings feature_settings_from_args(const Args& args);  // cmd_features.cpp
const std::vector<std::string>& feature_option_names();
const std::vector<std::string>& feature_flag_names();

namespace {
namespace fs = std::filesystem;

const char* kHelp = R"(usage: rollsense predict MODEL (TRIAL.csv | DATASET) [options]

Classify recordings with a saved model (model.rsm of a stock run, or the file
of 'rollsense train'). Each trial's input is computed as in training: the 13
features (the feature options below must be those of training; the defaults
are), or the prepared series for a classifier that takes series (prepared by
the series rule with the settings the model file records: channels, length,
amplitude and the rest, docs/series-preparation.md). A trial whose peaks are
not clean gets no decision, with the reason.

TRIAL.csv must lie in a dataset's trials/ folder (its dataset-info.csv names
the channels and the sample rate), and a TRIAL.csv that cannot be read is an
error (exit 3, or 5 when the system refuses the read); DATASET classifies every
trial of a dataset (one that cannot be read gets no decision, with the reason).

Warnings say when a trial is unlike the training data: another channel set or
sample rate than the training dataset's, a feature outside the range seen in
training, or a recorded object that is not a class of the model. The model file
holds none of these, so they come from the training run's dataset-info.csv and
features.csv, looked for beside MODEL (a stock run's output folder) or in
--training DIR; what cannot be checked is said once on stderr. The objects of
the training data's clean trials (features.csv) must be the model's classes (a
series model's are among its trials' objects): a --training DIR of other
objects is the wrong dataset (exit 2); MODEL's folder of others is not used.

options:
  --classifier NAME  the plugin that reads MODEL; default: the one the model
                     file names in its first word (rollsense-bagged-trees →
                     bagged_trees)
  --json             print a JSON array, one object per trial:
                     {trial_id, object, class, scores, reason, warnings}
  --training DIR     the training run's dataset folder, with its
                     dataset-info.csv and features.csv (default: MODEL's
                     folder); a folder that is not a dataset is refused
  --plugin-path DIR  search classifier plugins here first (repeatable)
  -v, --verbose      debug messages;   -q, --quiet   no info messages: warnings, errors
  plus the feature options of 'rollsense features')";

// A trial's outcome. `cls` empty = no decision (then `reason` says why).
struct Outcome {
    std::string trial_id, object, cls, reason;
    std::vector<double> scores;
    std::vector<std::string> warnings;
};

// What is known about the training data.
struct TrainingDescription {
    fs::path dir;
    std::optional<DatasetInfo> info;  // dataset-info.csv
    // Per feature, min and max over the clean training trials (features.csv).
    std::optional<std::array<std::pair<double, double>, features::kFeatureCount>> range;
    // The objects of its trials and of its clean trials (features.csv): a
    // feature model's classes are the latter, a series model's among the former.
    std::set<std::string> objects, clean_objects;
    std::vector<std::string> missing;  // what could not be found, for the note on stderr
};

TrainingDescription describe_training(const fs::path& dir) {
    TrainingDescription t;
    t.dir = dir;
    std::error_code ec;
    if (fs::exists(dir / "dataset-info.csv", ec)) {
        if (auto ds = DatasetReader::open(dir)) t.info = ds->info();
        else t.missing.push_back("dataset-info.csv unreadable (" + ds.error().message + ")");
    } else {
        t.missing.push_back("no dataset-info.csv (channel set and sample rate not checked)");
    }
    if (fs::exists(dir / "features.csv", ec)) {
        auto rows = features::read_features_csv(dir / "features.csv");
        if (rows) {
            std::array<std::pair<double, double>, features::kFeatureCount> r;
            r.fill({INFINITY, -INFINITY});
            bool any = false;
            for (const auto& row : *rows) {
                t.objects.insert(row.object);
                if (!row.clean) continue;
                any = true;
                t.clean_objects.insert(row.object);
                for (std::size_t f = 0; f < features::kFeatureCount; ++f) {
                    r[f].first = std::min(r[f].first, row.values[f]);
                    r[f].second = std::max(r[f].second, row.values[f]);
                }
            }
            if (any) t.range = r;
            else t.missing.push_back("features.csv has no clean trial (feature ranges not checked)");
        } else {
            t.missing.push_back("features.csv unreadable (" + rows.error().message + ")");
        }
    } else {
        t.missing.push_back("no features.csv (feature ranges not checked)");
    }
    return t;
}

std::string join(const std::vector<std::string>& v, const char* sep) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
    return out;
}

// A feature model's classes are the objects of the training run's clean trials
// (a series model's, objects it recorded: the series rule is not the peaks'): a
// folder whose features.csv says otherwise holds another dataset, and its
// channels and feature ranges would blame every trial. What differs, or nothing.
std::optional<std::string> other_classes(const TrainingDescription& t, const std::vector<std::string>& model_classes,
                                         ClassifierInput input) {
    const std::set<std::string> model(model_classes.begin(), model_classes.end());
    const auto& trained = input == ClassifierInput::features ? t.clean_objects : t.objects;
    const bool same = input == ClassifierInput::features ? trained == model
                                                         : std::includes(trained.begin(), trained.end(), model.begin(),
                                                                         model.end());
    if (trained.empty() || same) return std::nullopt;
    return std::string(input == ClassifierInput::features ? "its clean trials are of " : "its trials are of ") +
           join({trained.begin(), trained.end()}, ", ") + ", the model's classes " + join(model_classes, ", ");
}

// Warnings that hold for every trial of the input: channels and sample rate.
std::vector<std::string> dataset_warnings(const DatasetInfo& input, const TrainingDescription& t,
                                          const learn::ModelHeader& h) {
    std::vector<std::string> w;
    const std::vector<std::string>* trained = t.info ? &t.info->channels : (h.channels.empty() ? nullptr : &h.channels);
    if (trained && *trained != input.channels)
        w.push_back("channel set " + join(input.channels, ",") + " differs from training's " + join(*trained, ","));
    if (t.info && std::abs(input.sample_rate_hz - t.info->sample_rate_hz) > 0.01 * t.info->sample_rate_hz)
        w.push_back("sample rate " + csv::format_number(input.sample_rate_hz) + " Hz differs from training's " +
                    csv::format_number(t.info->sample_rate_hz) + " Hz");
    return w;
}

void range_warnings(const std::array<double, features::kFeatureCount>& x, const TrainingDescription& t,
                    std::vector<std::string>& w) {
    if (!t.range) return;
    for (std::size_t f = 0; f < features::kFeatureCount; ++f) {
        const auto [lo, hi] = (*t.range)[f];
        if (x[f] < lo || x[f] > hi)
            w.push_back(features::feature_names()[f] + " = " + csv::format_number(x[f]) +
                        " outside the training range [" + csv::format_number(lo) + ", " + csv::format_number(hi) +
                        "]");
    }
}

// A trial the classifier cannot decide keeps its reason; a prediction that
// breaks the plugin contract (learn::check_prediction) stops the command: no
// answer of that plugin can be trusted.
Status decide(const Classifier& clf, std::span<const double> input, Outcome& o) {
    auto p = clf.predict(input);
    if (!p) {
        if (p.error().code == ErrorCode::plugin_error)  // the trial it broke on (user review: not named)
            return Status(p.error()).with_context("trial '" + o.trial_id + "'");
        o.reason = "the classifier failed: " + p.error().describe();
        return {};
    }
    o.cls = p->class_name;
    o.scores = p->scores;
    return {};
}

// The trials to classify: a whole dataset, or one file of a dataset's trials/.
struct Input {
    DatasetReader dataset;
    std::vector<TrialRecord> trials;
};

Result<Input> open_input(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        auto ds = DatasetReader::open(path);
        if (!ds) return ds.error();
        std::vector<TrialRecord> trials = ds->trials();
        return Input{std::move(ds).value(), std::move(trials)};
    }
    if (!fs::exists(path, ec)) return Error{ErrorCode::not_found, path.string() + ": no such trial file or dataset"};
    const fs::path dir = fs::absolute(path).parent_path().parent_path();
    // Review: `predict MODEL RUN/features.csv` (train and evaluate take one) was told the file was not found.
    if (const fs::path folder = fs::absolute(path).parent_path(); holds_dataset(folder))
        return Error{ErrorCode::invalid_argument,
                     path.string() + " is a file of the dataset " + folder.string() + ", not one of its trials; "
                     "predict takes a trial file (" + (folder / "trials").string() + "/…) or a dataset folder: give " +
                     folder.string()};
    if (fs::absolute(path).parent_path().filename() != "trials" || !fs::exists(dir / "dataset-info.csv", ec))
        return Error{ErrorCode::not_found,
                     path.string() + ": a trial file must lie in a dataset's trials/ folder (its dataset-info.csv "
                                     "names the channels and the sample rate); copy the whole dataset folder"};
    auto ds = DatasetReader::open(dir);
    if (!ds) return ds.error();
    const std::string rel = "trials/" + path.filename().string();
    TrialRecord record;
    record.file = rel;
    record.info.id = path.stem().string();
    for (const auto& t : ds->trials())
        if (t.file == rel) record = t;  // listed in the manifest: its object is known
    return Input{std::move(ds).value(), {record}};
}

Result<std::vector<Outcome>> predict_features(const Classifier& clf, const Input& in,
                                              const features::FeatureSettings& fs_, const TrainingDescription& t) {
    std::vector<Outcome> out;
    features::FeatureExtractor extractor(fs_);
    // The channels and samples of features::extract_dataset.
    const auto columns = features::identification_channels(in.dataset.info(), in.dataset.dir().string());
    if (!columns) return columns.error();  // the dataset's fault, said once (review: it was each trial's, exit 0)
    for (const auto& rec : in.trials) {
        Outcome o{rec.info.id, rec.info.object, {}, {}, {}, {}};
        auto data = in.dataset.load(rec);
        if (!data) {
            o.reason = data.error().describe();
        } else {
            const features::IdentificationInput ch = features::identification_input(*data, *columns);
            auto f = extractor.extract(std::span<const std::span<const double>>(ch.channels), ch.time);
            if (!f) o.reason = f.error().describe();
            else if (!f->clean) o.reason = "no clean peaks: " + f->reason;
            else {
                range_warnings(f->values, t, o.warnings);
                if (auto s = decide(clf, f->values, o); !s) return s.error();
            }
        }
        out.push_back(std::move(o));
    }
    return out;
}

// The series rule of training, from the model file; one written before the
// file recorded it is prepared by the default rule with its length, and
// predict says so.
Result<std::vector<Outcome>> predict_series(const Classifier& clf, const Input& in, const learn::ModelHeader& h,
                                            const fs::path& model) {
    auto rule = series::model_rule(clf, model.string());
    if (!rule) return rule.error();
    series::SeriesSettings settings = rule->settings;
    if (!rule->recorded && h.series_length > 0) settings.length = h.series_length;
    if (rule->recorded && h.series_length > 0 && h.series_length != settings.length)
        return Error{ErrorCode::parse_error, "model file '" + model.string() + "': series_rule length=" +
                                                 std::to_string(settings.length) + " but series_length " +
                                                 std::to_string(h.series_length) +
                                                 ": the file was edited; train the model again"};
    if (!rule->recorded)
        std::fprintf(stderr, "rollsense predict: %s records no series rule (written before rollsense recorded it): "
                             "series prepared with its channels and length and the default rule of "
                             "docs/series-preparation.md; train it again if it used other settings\n",
                     model.c_str());
    const std::vector<std::string> channels = h.channels.empty() ? in.dataset.info().channels : h.channels;
    auto table = series::series_table(in.dataset, in.trials, channels, settings, 1);
    if (!table) return table.error();
    std::vector<Outcome> out;
    for (const auto& rec : in.trials) out.push_back({rec.info.id, rec.info.object, {}, {}, {}, {}});
    auto find = [&out](const std::string& id) -> Outcome& {
        return *std::find_if(out.begin(), out.end(), [&](const Outcome& o) { return o.trial_id == id; });
    };
    for (std::size_t r = 0; r < table->trial_ids.size(); ++r)
        if (auto s = decide(clf, table->table.row(r), find(table->trial_ids[r])); !s) return s.error();
    for (const auto& refused : table->refused) find(refused.trial_id).reason = "series refused: " + refused.reason;
    return out;
}

void print_text(const std::vector<Outcome>& outcomes, const std::vector<std::string>& classes) {
    std::printf("%-22s %-10s %-10s %6s  %s\n", "trial", "recorded", "class", "score", "runner-up");
    for (const auto& o : outcomes) {
        if (o.cls.empty()) {
            std::printf("%-22s %-10s %-10s %6s  %s\n", o.trial_id.c_str(), o.object.c_str(), "-", "-",
                        ("no decision: " + o.reason).c_str());
        } else {
            std::vector<std::size_t> order(o.scores.size());
            for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
            std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return o.scores[a] > o.scores[b]; });
            const std::size_t top = order.empty() ? 0 : order[0];
            // As the score, three decimals; none when no other class scored (review: "C1 0", an arbitrary class).
            std::string runner = "-";
            if (order.size() > 1 && order[1] < classes.size() && o.scores[order[1]] > 0) {
                char score[32];
                std::snprintf(score, sizeof score, " %.3f", o.scores[order[1]]);
                runner = classes[order[1]] + score;
            }
            std::printf("%-22s %-10s %-10s %6.3f  %s\n", o.trial_id.c_str(), o.object.c_str(), o.cls.c_str(),
                        top < o.scores.size() ? o.scores[top] : 0.0, runner.c_str());
        }
        for (const auto& w : o.warnings) std::printf("  warning: %s\n", w.c_str());
    }
}

void print_json(const std::vector<Outcome>& outcomes, const std::vector<std::string>& classes) {
    learn::JsonWriter j;
    j.begin_array();
    for (const auto& o : outcomes) {
        j.begin_object().key("trial_id").value(o.trial_id).key("object");
        if (o.object.empty()) j.null(); else j.value(o.object);
        j.key("class");
        if (o.cls.empty()) j.null(); else j.value(o.cls);
        j.key("scores").begin_object();
        for (std::size_t i = 0; i < o.scores.size() && i < classes.size(); ++i) j.key(classes[i]).value(o.scores[i]);
        j.end_object().key("reason");
        if (o.reason.empty()) j.null(); else j.value(o.reason);
        j.key("warnings").begin_array();
        for (const auto& w : o.warnings) j.value(w);
        j.end_array().end_object();
    }
    j.end_array();
    std::printf("%s\n", j.str().c_str());
}

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    std::vector<std::string> known = feature_option_names();
    known.insert(known.end(), feature_flag_names().begin(), feature_flag_names().end());
    for (const char* k : {"--classifier", "--json", "--training", "--plugin-path", "-v", "--verbose", "-q", "--quiet"})
        known.emplace_back(k);
    args.reject_unknown(known);
    setup_logging(args);
    std::vector<std::string> valued = feature_option_names();
    valued.insert(valued.end(), {"--classifier", "--training", "--plugin-path"});
    const auto pos = args.positionals(valued);
    if (pos.size() != 2) throw UsageError("expects MODEL and a TRIAL.csv or DATASET (see rollsense predict --help)");
    const fs::path model = pos[0];
    const auto settings = feature_settings_from_args(args);
    std::vector<fs::path> extra;
    for (const auto& p : args.options("--plugin-path")) extra.emplace_back(p);
    auto fail = [](const Error& e, int fallback) {
        std::fprintf(stderr, "rollsense predict: %s\n", e.describe().c_str());
        return exit_code_for(e.code, fallback);
    };

    auto header = learn::read_model_header(model);
    // A folder given as MODEL (the arguments swapped) is the command line's mistake, 2 (first-day review: 3).
    if (!header) return fail(header.error(), header.error().code == ErrorCode::invalid_argument ? kExitUsage : kExitConfig);
    std::string plugin = args.option("--classifier");
    const bool inferred = plugin.empty();
    if (inferred) {
        auto named = learn::plugin_named_by(*header, model);
        if (!named) return fail(named.error(), kExitConfig);
        plugin = *named;
    }
    runtime::PluginRegistry registry(runtime::PluginRegistry::default_search_path(extra));
    auto factory = learn::plugin_classifier_factory(registry, plugin);
    if (!factory) {
        Error e = factory.error();
        if (inferred) e.message += learn::named_by_note(model, "give --classifier NAME");
        return fail(e, kExitConfig);
    }
    auto clf = (*factory)(ParamSet{});
    if (!clf) return fail(clf.error(), kExitConfig);
    if (auto st = (*clf)->load(model); !st) return fail(st.error(), kExitConfig);  // the error names the plugin
    const auto classes = (*clf)->class_names();

    auto input = open_input(pos[1]);
    if (!input) return fail(input.error(), kExitConfig);
    // One named trial that cannot be read is the input's error, not a trial without a decision (review: exit 0).
    if (std::error_code ec; !fs::is_directory(pos[1], ec))
        if (auto data = input->dataset.load(input->trials.front()); !data)
            return fail(Error{data.error().code, data.error().message + "; restore the file, or record the trial again"},
                        kExitConfig);

    const auto named_training = args.options("--training");  // an existing folder (Args)
    const fs::path training_dir = named_training.empty() ? fs::absolute(model).parent_path()
                                                         : fs::path(named_training.back());
    TrainingDescription training = describe_training(training_dir);
    if (!named_training.empty() && !training.info)
        throw UsageError("--training " + training_dir.string() + " is not a dataset folder (" +
                         (fs::exists(training_dir / "dataset-info.csv") ? training.missing.front()
                                                                        : std::string("it has no dataset-info.csv")) +
                         "): give the output folder of the run the model was trained on, or leave the option out");
    if (auto other = other_classes(training, classes, (*clf)->input())) {
        if (!named_training.empty())
            throw UsageError("--training " + training_dir.string() + " is not the dataset " + model.string() +
                             " was trained on: " + *other + "; give that run's output folder");
        training = TrainingDescription{};  // MODEL's folder: not the training data, so nothing is checked against it
        training.dir = training_dir;
        training.missing.push_back("it holds another dataset (" + *other + ")");
    }
    if (!training.missing.empty())  // the way to the check (first-day review: none was said)
        std::fprintf(stderr, "rollsense predict: not checked against the training data, in %s: %s%s\n",
                     training_dir.c_str(), join(training.missing, "; ").c_str(),
                     named_training.empty() ? "; give --training DIR, the output folder of the run the model was "
                                              "trained on, to check the trials against its range"
                                            : "");

    std::vector<Outcome> outcomes;
    if ((*clf)->input() == ClassifierInput::series) {
        auto s = predict_series(**clf, *input, *header, model);
        if (!s) return fail(s.error(), kExitConfig);
        outcomes = std::move(s).value();
    } else {
        auto f = predict_features(**clf, *input, settings, training);
        if (!f) return fail(f.error(), kExitConfig);
        outcomes = std::move(f).value();
    }
    const auto common = dataset_warnings(input->dataset.info(), training, *header);
    for (auto& o : outcomes) {
        o.warnings.insert(o.warnings.begin(), common.begin(), common.end());
        if (!o.object.empty() && std::find(classes.begin(), classes.end(), o.object) == classes.end())
            o.warnings.push_back("recorded object '" + o.object + "' is not a class of the model (" +
                                 join(classes, ", ") + "): the answer can only be one of those");
    }
    if (args.flag("--json")) print_json(outcomes, classes);
    else print_text(outcomes, classes);
    return kExitOk;
}

const Registration reg{{"predict", "classify a trial or a dataset with a saved model", kHelp, &run}};

}  // namespace
}  // namespace rollsense::cli
