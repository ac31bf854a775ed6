#include "analysis/learn/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>

#include "rollsense/atomic_file.hpp"
#include "rollsense/dataset.hpp"
#include "analysis/learn/bayes_opt.hpp"
#include "analysis/learn/checked_classifier.hpp"
#include "analysis/learn/evaluation_json.hpp"
#include "analysis/learn/inputs.hpp"
#include "analysis/learn/plugin_factory.hpp"
#include "analysis/learn/prefix_evaluation.hpp"
#include "analysis/series/series_table.hpp"

namespace rollsense::learn {

std::string spec_name(const std::string& plugin, const ParamSet& own) {
    std::string name = plugin;
    for (const auto& [k, v] : own.values()) name += ":" + k + "=" + format_param_value(v);
    return name;
}

void make_names_unique(std::vector<ClassifierSpec>& specs) {
    std::map<std::string, int> seen;
    for (auto& s : specs)
        if (const int n = ++seen[s.name]; n > 1) s.name += " #" + std::to_string(n);
}

Result<std::vector<ClassifierSpec>> parse_classifier_list(const std::string& text, const ParamSet& common) {
    std::vector<ClassifierSpec> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find(',', start);
        if (end == std::string::npos) end = text.size();
        const std::string entry = text.substr(start, end - start);
        start = end + 1;
        if (entry.empty())
            return Error{ErrorCode::invalid_argument, "classifier list '" + text +
                                                          "' has an empty entry (write NAME[,NAME...], an entry "
                                                          "optionally NAME:KEY=VALUE)"};
        ClassifierSpec spec;
        ParamSet own;
        std::size_t colon = entry.find(':');
        spec.plugin = entry.substr(0, colon);
        if (spec.plugin.empty())
            return Error{ErrorCode::invalid_argument, "classifier entry '" + entry + "' has no plugin name before ':'"};
        while (colon != std::string::npos) {
            const std::size_t next = entry.find(':', colon + 1);
            const std::string assignment = entry.substr(colon + 1, next == std::string::npos ? next : next - colon - 1);
            if (auto st = parse_assignment(assignment, own); !st)
                return Error{st.code(), "classifier entry '" + entry + "': " + st.message()};
            colon = next;
        }
        spec.params = common;
        for (const auto& [k, v] : own.values()) spec.params.set(k, v);
        spec.name = spec_name(spec.plugin, own);
        out.push_back(std::move(spec));
        if (end == text.size()) break;
    }
    make_names_unique(out);
    return out;
}

Result<std::vector<PreparedClassifier>> prepare_classifiers(runtime::PluginRegistry& registry,
                                                            const std::vector<ClassifierSpec>& specs) {
    if (specs.empty()) return Error{ErrorCode::invalid_argument, "no classifier requested"};
    // Every name first, so one typo in a list of several costs no extraction or training.
    for (const auto& s : specs)
        if (auto st = find_classifier_plugin(registry, s.plugin); !st) return st.error();
    std::vector<PreparedClassifier> out;
    for (const auto& s : specs) {
        auto factory = plugin_classifier_factory(registry, s.plugin);
        if (!factory) return factory.error();
        // One instance now: checks the parameters and tells the input kind.
        auto probe = (*factory)(s.params);
        if (!probe) return in_classifier(probe.error(), s.name);
        out.push_back({s, std::move(factory).value(), (*probe)->input()});
    }
    return out;
}

std::string_view to_string(TrialSelection t) noexcept {
    return t == TrialSelection::paper_clean ? "clean" : "all";
}

Result<TrialSelection> parse_trial_selection(std::string_view text) {
    if (text == "clean" || text == "paper_clean") return TrialSelection::paper_clean;
    if (text == "all" || text == "series_accepted") return TrialSelection::series_accepted;
    return Error{ErrorCode::invalid_argument,
                 "trials '" + std::string(text) +
                     "' is not a trial selection: write 'clean' (the paper's clean trials, default) or 'all' "
                     "(every trial the series rule accepts; series classifiers only)"};
}

Result<series::Amplitude> parse_amplitude(std::string_view text) {
    if (text == "global_scale") return series::Amplitude::global_scale;
    if (text == "z_per_channel") return series::Amplitude::z_per_channel;
    return Error{ErrorCode::invalid_argument, "series amplitude '" + std::string(text) +
                                                  "' is not a mode: write 'global_scale' or 'z_per_channel' "
                                                  "(docs/series-preparation.md)"};
}

Result<series::TimeAxis> parse_time_axis(std::string_view text) {
    if (text == "contact") return series::TimeAxis::contact;
    if (text == "roll_relative") return series::TimeAxis::roll_relative;
    return Error{ErrorCode::invalid_argument,
                 "series time axis '" + std::string(text) +
                     "' is not a mode: write 'contact' (the paper's timing rule, default) or 'roll_relative' (" +
                     kOutsideTimingRule + ", for comparison only; docs/series-preparation.md)"};
}

Result<std::vector<std::string>> series_channels(const DatasetInfo& info, const std::string& dataset) {
    auto columns = features::identification_channels(info, dataset);
    if (!columns) return columns.error();
    std::vector<std::string> names;
    for (const std::size_t c : *columns) names.push_back(info.channels[c]);
    return names;
}

namespace {

// The series rule's verdict on every trial of the dataset, by trial id.
struct SeriesVerdicts {
    series::SeriesTable table;
    std::map<std::string, std::size_t> row_of_trial;  // accepted: row in table
    std::map<std::string, std::string> refused;       // refused: reason
};

Result<SeriesVerdicts> prepare_all_series(const std::filesystem::path& dataset_dir, const InputOptions& options) {
    auto ds = DatasetReader::open(dataset_dir);
    if (!ds) return ds.error();
    auto channels = series_channels(ds->info(), dataset_dir.string());
    if (!channels) return channels.error();
    auto st = series::series_table(*ds, ds->trials(), *channels, options.series, options.threads);
    if (!st) return st.error();
    SeriesVerdicts v;
    v.table = std::move(st).value();
    for (std::size_t i = 0; i < v.table.trial_ids.size(); ++i) v.row_of_trial[v.table.trial_ids[i]] = i;
    for (const auto& r : v.table.refused) v.refused[r.trial_id] = r.reason;
    return v;
}

}  // namespace

namespace {
// `needs` ("X needs", "Y need") the recorded trials: `input` must be a dataset folder.
Status input_holds_trials(const std::filesystem::path& input, const std::string& needs) {
    std::error_code ec;
    if (!input.empty() && std::filesystem::is_directory(input, ec)) return {};
    return {ErrorCode::invalid_argument,
            needs + " the recorded trials, but " +
                (input.empty() ? std::string("the input is not a dataset folder (none was given)")
                               : "the input '" + input.string() + "' is not a dataset folder") +
                " (a features CSV holds only the 13 features of each trial): pass the dataset folder it was made from"};
}
}  // namespace

Status check_input_holds_trials(const std::filesystem::path& input, const std::vector<PreparedClassifier>& classifiers,
                                bool prefixes) {
    for (const auto& c : classifiers)
        if (c.input == ClassifierInput::series)
            return input_holds_trials(input, "classifier '" + c.spec.name + "' takes the prepared series (input() = "
                                             "series) and needs");
    if (prefixes) return input_holds_trials(input, "the prefix curves (--prefixes) need");
    return {};
}

Status check_input_options(const std::vector<ClassifierInput>& kinds, const InputOptions& options) {
    const bool need_features = std::ranges::count(kinds, ClassifierInput::features) > 0;
    const bool need_series = std::ranges::count(kinds, ClassifierInput::series) > 0;
    const series::SeriesSettings preset;
    // Review: --series-amplitude with a feature classifier was ignored without a word.
    const bool axis = options.time_axis_named || options.series.time_axis != preset.time_axis;
    if (!need_series && (axis || options.amplitude_named || options.series.amplitude != preset.amplitude))
        return {ErrorCode::invalid_argument,
                "the series rule's " +
                    std::string(axis
                                    ? "time axis " + std::string(series::to_string(options.series.time_axis)) +
                                          " (--series-time-axis, series_time_axis)"
                                    : "amplitude " + std::string(series::to_string(options.series.amplitude)) +
                                          " (--series-amplitude, series_amplitude)") +
                    " applies to series classifiers (minirocket), but every classifier listed takes the 13 "
                    "features: list a series classifier, or drop it"};
    if (options.trials == TrialSelection::series_accepted && need_features)
        return {ErrorCode::invalid_argument,
                "trials=all (--trials all) takes every trial the series rule accepts, but a feature classifier has no "
                "features for the trials the paper's peak rule refuses: evaluate it with trials=clean, or "
                "list only series classifiers"};
    return {};
}

Status check_input_options(const std::vector<PreparedClassifier>& classifiers, const InputOptions& options) {
    std::vector<ClassifierInput> kinds;
    for (const auto& c : classifiers) kinds.push_back(c.input);
    return check_input_options(kinds, options);
}

Result<InputTables> make_input_tables(const std::vector<features::FeatureRow>& rows,
                                      const std::filesystem::path& dataset_dir,
                                      const std::vector<ClassifierInput>& kinds, const InputOptions& options) {
    const bool need_features =
        std::find(kinds.begin(), kinds.end(), ClassifierInput::features) != kinds.end();
    const bool need_series = std::find(kinds.begin(), kinds.end(), ClassifierInput::series) != kinds.end();
    if (!need_features && !need_series) return Error{ErrorCode::invalid_argument, "no classifier input kind given"};
    if (auto st = check_input_options(kinds, options); !st) return st.error();
    std::optional<SeriesVerdicts> sv;
    if (need_series) {
        if (auto st = input_holds_trials(dataset_dir, "a series classifier (input() = series) needs"); !st) return st.error();
        auto v = prepare_all_series(dataset_dir, options);
        if (!v) return v.error();
        sv = std::move(v).value();
    }

    InputTables in;
    in.selection = options.trials == TrialSelection::paper_clean ? "paper_clean" : "series_accepted";
    if (need_series) in.series_time_axis = std::string(series::to_string(options.series.time_axis));
    std::map<std::string, int> classes;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const auto& row = rows[r];
        const bool peak_ok = options.trials == TrialSelection::series_accepted || row.clean;
        bool series_ok = true;
        std::string why;
        // With features only the reason reads as it always did; beside the
        // series rule each reason says which rule gave it.
        if (!peak_ok) why = (sv ? "peak rule: " : "") + (row.reason.empty() ? std::string("not clean") : row.reason);
        if (sv) {
            if (auto it = sv->refused.find(row.trial_id); it != sv->refused.end()) {
                series_ok = false;
                why += (why.empty() ? "" : "; ") + std::string("series rule: ") + it->second;
            } else if (!sv->row_of_trial.count(row.trial_id)) {
                return Error{ErrorCode::invalid_argument, "trial '" + row.trial_id +
                                                              "' has features but is not in the dataset's manifest "
                                                              "(features and dataset out of step?)"};
            }
        }
        if (peak_ok && series_ok) {
            in.row_of.push_back(r);
            classes.emplace(row.object, 0);
        } else {
            in.refused.push_back({row.trial_id, why});
        }
    }
    std::vector<std::string> class_names;
    for (auto& [name, label] : classes) {
        label = static_cast<int>(class_names.size());
        class_names.push_back(name);
    }
    if (need_features) {
        FeatureTable t;
        t.feature_names.assign(features::feature_names().begin(), features::feature_names().end());
        t.class_names = class_names;
        for (std::size_t r : in.row_of) {
            t.x.insert(t.x.end(), rows[r].values.begin(), rows[r].values.end());
            t.y.push_back(classes[rows[r].object]);
            ++t.rows;
        }
        in.tables.push_back(std::move(t));
        in.kinds.push_back("features");
    }
    if (need_series) {
        const FeatureTable& src = sv->table.table;
        const std::size_t width = src.cols();
        FeatureTable t;
        t.channel_names = src.channel_names;
        t.series_length = src.series_length;
        t.series_rule = src.series_rule;  // saved with the model (series/model_rule.hpp)
        t.class_names = class_names;
        t.x.reserve(in.row_of.size() * width);
        for (std::size_t r : in.row_of) {
            const std::size_t i = sv->row_of_trial.at(rows[r].trial_id);
            t.x.insert(t.x.end(), src.x.begin() + static_cast<std::ptrdiff_t>(i * width),
                       src.x.begin() + static_cast<std::ptrdiff_t>((i + 1) * width));
            t.y.push_back(classes[rows[r].object]);
            ++t.rows;
        }
        in.tables.push_back(std::move(t));
        in.kinds.push_back("series");
    }
    return in;
}

namespace {
std::size_t table_of(const InputTables& in, ClassifierInput kind) {
    const std::string want = kind == ClassifierInput::series ? "series" : "features";
    return static_cast<std::size_t>(std::find(in.kinds.begin(), in.kinds.end(), want) - in.kinds.begin());
}
}  // namespace

namespace {
// evaluate_prepared, telling fold options the selected trials cannot take
// (`failed` = options) from the evaluation's own failures.
Result<Evaluation> evaluate_prepared_staged(const std::vector<features::FeatureRow>& rows,
                                            const std::filesystem::path& dataset_dir,
                                            const std::vector<PreparedClassifier>& classifiers,
                                            const EvaluationOptions& options, const InputOptions& inputs,
                                            PipelineStage& failed) {
    failed = PipelineStage::evaluation;
    if (classifiers.empty()) return Error{ErrorCode::invalid_argument, "no classifier to evaluate"};
    std::vector<ClassifierInput> kinds;
    for (const auto& c : classifiers) kinds.push_back(c.input);
    auto input = make_input_tables(rows, dataset_dir, kinds, inputs);
    if (!input) return input.error();
    if (auto st = check_fold_options(rows, input->row_of.size(), options); !st) {
        failed = PipelineStage::options;
        return st.error();
    }
    std::vector<ClassifierRequest> requests;
    for (const auto& c : classifiers)
        requests.push_back({c.spec.name, c.factory, c.spec.params, table_of(*input, c.input)});
    return evaluate_tables(rows, *input, requests, options);
}
}  // namespace

Result<Evaluation> evaluate_prepared(const std::vector<features::FeatureRow>& rows,
                                     const std::filesystem::path& dataset_dir,
                                     const std::vector<PreparedClassifier>& classifiers,
                                     const EvaluationOptions& options, const InputOptions& inputs) {
    PipelineStage failed;
    return evaluate_prepared_staged(rows, dataset_dir, classifiers, options, inputs, failed);
}

std::uint64_t recorded_partition_seed(const std::filesystem::path& input, std::uint64_t fallback) {
    std::error_code ec;
    if (!std::filesystem::is_directory(input, ec)) return fallback;
    auto dataset = DatasetReader::open(input);
    return dataset && dataset->info().seed != 0 ? dataset->info().seed : fallback;
}

Status check_tunable(const std::vector<PreparedClassifier>& classifiers, const EvaluationOptions& options) {
    if (!options.optimize) return {};
    for (const auto& c : classifiers)  // user review: the others' tuning ran 98 s before one with nothing to tune failed
        if (auto space = tuning_space(c.factory, c.spec.params, kProbeRows, kProbeCols, options.space, c.spec.name); !space)
            return space.error();
    return {};
}

Status check_final_fit(const PreparedClassifier& classifier, const EvaluationOptions& options) {
    if (auto st = check_final_tuning(options); !st) return st;
    if (classifier.input == ClassifierInput::series && options.optimize)
        return {ErrorCode::unsupported, "classifier '" + classifier.spec.name +
                                            "': tuning the deployed model is implemented for feature "
                                            "classifiers only; train it with its preset (no optimize)"};
    return {};
}

Result<FinalModel> fit_final_prepared(const std::vector<features::FeatureRow>& rows,
                                      const std::filesystem::path& dataset_dir, const PreparedClassifier& classifier,
                                      const EvaluationOptions& options, const InputOptions& inputs) {
    EvaluationOptions o = options;
    o.params = classifier.spec.params;
    if (classifier.input == ClassifierInput::features && inputs.trials == TrialSelection::paper_clean)
        return fit_final(rows, classifier.factory, o);  // the paper's model, exactly as before
    if (auto st = check_final_fit(classifier, o); !st) return st.error();
    auto input = make_input_tables(rows, dataset_dir, {classifier.input}, inputs);
    if (!input) return input.error();
    const FeatureTable& table = input->tables.front();
    if (table.rows == 0) return Error{ErrorCode::invalid_argument, "no trials to train on"};
    if (auto st = check_two_classes(table, "training"); !st) return st.error();
    auto model = train_classifier(table, classifier.factory, o.params);
    if (!model) return model.error();
    FinalModel out;
    out.params = o.params;
    out.classifier = std::move(model).value();
    return out;
}

namespace {

// Every classifier the evaluation trains is made by its factory (each fold,
// each optimiser point, nested folds, prefixes, the final model): checking
// the stop flag there ends any of them within one training.
ClassifierFactory stoppable(ClassifierFactory factory, const std::atomic<bool>* stop) {
    if (!stop) return factory;
    return [factory = std::move(factory), stop](const ParamSet& params) -> Result<ClassifierPtr> {
        if (stop->load()) return Error{ErrorCode::cancelled, "interrupted by Ctrl-C or a SIGTERM/SIGHUP: the evaluation stopped"};
        return factory(params);
    };
}

}  // namespace

Result<PipelineResult> run_pipeline(runtime::PluginRegistry& registry, const PipelineRequest& request,
                                    const std::function<Status(const std::vector<features::FeatureRow>&)>& on_rows,
                                    PipelineStage* failed) {
    auto fail = [failed](PipelineStage stage, Error e) -> Result<PipelineResult> {
        if (failed) *failed = stage;
        return e;
    };
    PipelineResult out;
    auto prepared = prepare_classifiers(registry, request.classifiers);
    if (!prepared) return fail(PipelineStage::classifiers, prepared.error());
    out.classifiers = std::move(prepared).value();
    if (auto st = check_input_holds_trials(request.input, out.classifiers, request.prefixes.has_value()); !st)
        return fail(PipelineStage::request, st.error());
    if (auto st = check_input_options(out.classifiers, request.inputs); !st) return fail(PipelineStage::request, st.error());
    if (auto st = check_tunable(out.classifiers, request.options); !st) return fail(PipelineStage::classifiers, st.error());
    for (auto& c : out.classifiers) c.factory = stoppable(std::move(c.factory), request.options.stop);
    auto rows = load_feature_rows(request.input, request.features, 0, request.options.stop, request.recorded);
    if (!rows) return fail(PipelineStage::rows, rows.error());
    out.rows = std::move(rows).value();
    if (on_rows)
        if (auto st = on_rows(out.rows); !st) return fail(PipelineStage::rows, st.error());
    // A features CSV passes as itself: what needs the trials was refused above, naming it.
    const auto& dataset_dir = request.input;
    PipelineStage stage;
    auto ev = evaluate_prepared_staged(out.rows, dataset_dir, out.classifiers, request.options, request.inputs, stage);
    if (!ev) return fail(stage, ev.error());
    out.evaluation = std::move(ev).value();
    if (request.prefixes) {
        PrefixOptions po = *request.prefixes;
        if (!po.progress) po.progress = request.options.progress;
        const auto started = std::chrono::steady_clock::now();
        auto curves = prefix_curves(dataset_dir, out.evaluation, out.classifiers, request.features,
                                    request.inputs, po);
        if (!curves) return fail(PipelineStage::evaluation, curves.error());
        out.evaluation.prefixes = std::move(curves).value();
        // `seconds` is the whole evaluation's wall time (evaluation-json.md): the curves' too (review: "6.0 s" said
        // of an evaluate --prefixes that took 70 s).
        out.evaluation.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    }
    return out;
}

EvaluationFiles evaluation_files(const std::filesystem::path& output) {
    EvaluationFiles f{output, output};
    if (output.extension() == ".json") f.text.replace_extension(".txt");
    else f.json.replace_extension(".json");
    return f;
}

Status write_evaluation_files(const Evaluation& evaluation, const EvaluationFiles& files) {
    if (auto st = write_file_atomic(files.text, format_evaluation(evaluation)); !st)
        return {st.code(), "cannot write '" + files.text.string() + "': " + st.message()};
    if (auto st = write_file_atomic(files.json, evaluation_json(evaluation)); !st)
        return {st.code(), "cannot write '" + files.json.string() + "': " + st.message()};
    return {};
}

}  // namespace rollsense::learn
