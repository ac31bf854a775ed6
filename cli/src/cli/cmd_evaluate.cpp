// rollsense evaluate INPUT: how well a classifier identifies the objects, with
// the paper's protocol and the honest one side by side.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "cli/output_paths.hpp"
#include "cli/partial_dataset.hpp"
#include "cli/trial_warnings.hpp"
#include "cli/paths.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/atomic_file.hpp"
#include "analysis/learn/defaults.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/inputs.hpp"
#include "analysis/learn/pipeline.hpp"
#include "analysis/learn/plugin_factory.hpp"
#include "runtime/session/safety.hpp"

namespace rollsense::cli {

features::FeatureSettings feature_settings_from_args(const Args& args);  // cmd_features.cpp
const std::vector<std::string>& feature_option_names();                  // cmd_features.cpp
const std::vector<std::string>& feature_flag_names();                    // cmd_features.cpp
using LearnSetup = learn::CommandSetup;

namespace {

template <typename T>
T value_or_throw_usage(Result<T> r, const std::string& option) {
    if (!r) throw UsageError(option + ": " + r.error().message);
    return std::move(r).value();
}

int integer_option(const Args& args, std::string_view name, int fallback, int min) {
    const std::string v = args.option(name);
    if (v.empty()) return fallback;
    try {
        std::size_t used = 0;
        const int i = std::stoi(v, &used);
        if (used != v.size() || i < min) throw std::invalid_argument(v);
        return i;
    } catch (const std::exception&) {
        throw UsageError(std::string(name) + " expects an integer >= " + std::to_string(min) + ", got '" + v + "'");
    }
}

}  // namespace

namespace {
const std::vector<std::string> kLearnOptions = {"--folds",      "--repeats",     "--seed",   "--evaluations",
                                                "--classifier", "--set",         "--plugin-path", "-o",
                                                "--output",     "--trials",      "--series-amplitude",
                                                "--series-time-axis",            "--cv",
                                                "--group-by",   "--block"};
// Grouped and blocked CV: evaluate and report; train takes them with
// --optimize only, for its tuning folds (it fits one model, no CV).
const std::vector<std::string> kCvSchemeOptions = {"--cv", "--group-by", "--block"};
}  // namespace

// Options that set the optimiser: given without --optimize they would be
// ignored, so they are refused, naming the way out.
void require_optimize(const Args& args, const std::vector<std::string>& options) {
    if (args.flag("--optimize")) return;
    for (const auto& o : options)
        if (args.given(o))
            throw UsageError(o + " applies with --optimize only (it sets the optimiser); add --optimize or drop " + o);
}

// Shared by evaluate, report and train (declared again in cmd_report.cpp and
// cmd_train.cpp). `not_taken`: options of the learning commands this command has
// no use for, refused as unknown.
LearnSetup learn_setup_from_args(const Args& args, const std::vector<std::string>& extra_flags,
                                 const std::vector<std::string>& not_taken) {
    std::vector<std::string> known;
    for (const auto& o : kLearnOptions)
        if (std::find(not_taken.begin(), not_taken.end(), o) == not_taken.end()) known.push_back(o);
    known.insert(known.end(), feature_option_names().begin(), feature_option_names().end());
    known.insert(known.end(), feature_flag_names().begin(), feature_flag_names().end());
    known.insert(known.end(), extra_flags.begin(), extra_flags.end());
    for (const char* k : {"-v", "--verbose", "-q", "--quiet"}) known.emplace_back(k);
    args.reject_unknown(known);
    require_optimize(args, {"--evaluations", "--no-nested"});
    std::vector<std::string> valued = kLearnOptions;
    valued.insert(valued.end(), feature_option_names().begin(), feature_option_names().end());
    const auto pos = args.positionals(valued);
    if (pos.size() != 1) throw UsageError("expected one INPUT: a dataset folder or a features CSV");
    LearnSetup s;
    s.input = pos[0];
    // Review: `train features.csv --smoothing-factor 0.2` used the table's features as they were, without a word.
    if (std::error_code ec; std::filesystem::is_regular_file(s.input, ec)) {
        std::vector<std::string> given;
        for (const auto& o : feature_option_names())
            if (o != "--threads" && !args.option(o).empty()) given.push_back(o);
        for (const auto& f : feature_flag_names())
            if (args.flag(f)) given.push_back(f);
        if (!given.empty())
            throw UsageError(given.front() + " sets how features are computed from a dataset's trials; " + pos[0] +
                             " is a features table, computed already: give the dataset folder it came from");
    }
    auto& o = s.options;
    o.folds = integer_option(args, "--folds", o.folds, 2);
    o.repeats = integer_option(args, "--repeats", o.repeats, 1);
    o.seed = static_cast<std::uint64_t>(integer_option(args, "--seed", static_cast<int>(o.seed), 0));
    // The seed the run's rs.analyse evaluated with, unless --seed says otherwise: evaluate DATASET gives the run's own
    // figures (review: evaluate said 75.9 % of a run whose evaluation.txt and report said 76.2 %).
    if (args.option("--seed").empty()) o.seed = learn::recorded_partition_seed(s.input, o.seed);
    o.optimize = args.flag("--optimize");
    o.nested = !args.flag("--no-nested");
    o.bayes.evaluations = integer_option(args, "--evaluations", o.bayes.evaluations, 1);
    s.classifier = value_or_throw(learn::classifier_or_default(args.option("--classifier"), share_dir()));
    o.classifier = s.classifier;
    for (const auto& a : args.options("--set"))
        if (auto st = learn::parse_assignment(a, o.params); !st) throw UsageError(st.message());
    for (const auto& p : args.options("--plugin-path")) s.plugin_path.emplace_back(p);
    o.schemes = value_or_throw_usage(
        learn::parse_cv_schemes(args.option("--cv"), args.option("--group-by"), args.option("--block")), "--cv");
    return s;
}

// The classifier list of --classifier (with --set for all), or a usage error.
std::vector<learn::ClassifierSpec> classifier_specs(const LearnSetup& s) {
    auto specs = learn::parse_classifier_list(s.classifier, s.options.params);
    if (!specs) throw UsageError("--classifier: " + specs.error().message);
    return std::move(specs).value();
}

// --trials, --series-amplitude and --series-time-axis (evaluate and report
// only): the input step's trial selection and the series rule's amplitude and
// time axis (docs/series-preparation.md).
learn::InputOptions input_options_from_args(const Args& args) {
    learn::InputOptions in;
    if (const auto t = args.option("--trials"); !t.empty())
        in.trials = value_or_throw_usage(learn::parse_trial_selection(t), "--trials");
    if (const auto a = args.option("--series-amplitude"); !a.empty()) {
        in.series.amplitude = value_or_throw_usage(learn::parse_amplitude(a), "--series-amplitude");
        in.amplitude_named = true;
    }
    if (const auto t = args.option("--series-time-axis"); !t.empty()) {
        in.series.time_axis = value_or_throw_usage(learn::parse_time_axis(t), "--series-time-axis");
        in.time_axis_named = true;
    }
    return in;
}

// A classifier that cannot be set up: a bad parameter (--set, a list entry's
// KEY=VALUE) is the command line's (2); a missing or broken plugin is configuration (3).
int classifier_setup_exit(ErrorCode code) {
    return code == ErrorCode::invalid_argument ? kExitUsage : exit_code_for(code, kExitConfig);
}

// The learning pipeline for evaluate and report, with the command's exit codes:
// a wrong INPUT or plugin is a configuration error, a failed evaluation a failure.
// The clean count and rejections are printed once the features exist, unless the
// command's own summary prints them (report).
int run_learning_pipeline(const char* command, const Args& args, const LearnSetup& s,
                          runtime::PluginRegistry& registry, learn::PipelineResult& out, bool print_rejections) {
    learn::PipelineRequest request;
    request.input = s.input;
    request.features = feature_settings_from_args(args);
    request.classifiers = classifier_specs(s);
    request.options = s.options;
    request.inputs = input_options_from_args(args);
    if (args.flag("--prefixes")) {
        learn::PrefixOptions po;
        // One k-fold per fraction unless --repeats asks for more.
        if (!args.option("--repeats").empty()) po.repeats = s.options.repeats;
        request.prefixes = po;
    }
    request.options.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    // Ctrl-C (or SIGTERM/SIGHUP) stops the evaluation at its next training: exit 130.
    std::atomic<bool> interrupted{false};
    runtime::InterruptGuard on_interrupt(interrupted);
    request.options.stop = &interrupted;
    learn::PipelineStage failed = learn::PipelineStage::evaluation;
    auto result = learn::run_pipeline(
        registry, request,
        [print_rejections](const std::vector<features::FeatureRow>& rows) {
            if (auto unread = warn_unreadable_trials(rows); !unread) return unread;
            // On stderr: stdout is the evaluation's text alone, as evaluation.txt holds it.
            if (print_rejections) std::fprintf(stderr, "%s\n", learn::summarize_rejections(rows).c_str());
            return Status{};
        },
        &failed);
    if (!result) {
        std::fprintf(stderr, "rollsense %s: %s\n", command, result.error().describe().c_str());
        if (failed == learn::PipelineStage::classifiers) return classifier_setup_exit(result.error().code);
        if (failed == learn::PipelineStage::request) return kExitUsage;  // e.g. a features CSV for a series classifier
        if (failed == learn::PipelineStage::options) return kExitUsage;  // --folds or --group-by the trials cannot take
        return exit_code_for(result.error().code,
                             failed == learn::PipelineStage::evaluation ? kExitFailure : kExitConfig);
    }
    out = std::move(result).value();
    return kExitOk;
}

// Rows (from a dataset or a features file), the one prepared classifier and
// the input step's options (--trials, --series-amplitude) for rollsense train:
// everything that does not go together is refused before the rows are read.
int prepare(const char* command, const Args& args, const LearnSetup& s, runtime::PluginRegistry& registry,
            std::vector<features::FeatureRow>& rows, learn::PreparedClassifier& classifier,
            learn::InputOptions& inputs) {
    for (const auto& o : kCvSchemeOptions)
        if (!args.option(o).empty() && !s.options.optimize)
            throw UsageError(o + " applies to " + command + " with --optimize only (the tuning folds follow it); " +
                             command + " fits one model on every selected trial, without cross-validation");
    const auto specs = classifier_specs(s);
    if (specs.size() != 1)
        throw UsageError(std::string(command) + " takes one classifier, got '" + s.classifier + "'");
    inputs = input_options_from_args(args);
    // The plugin and its parameters first, before minutes of extraction.
    auto prepared = learn::prepare_classifiers(registry, specs);
    if (!prepared) {
        std::fprintf(stderr, "rollsense %s: %s\n", command, prepared.error().describe().c_str());
        return classifier_setup_exit(prepared.error().code);
    }
    classifier = prepared->front();
    for (const Status& st : {learn::check_input_holds_trials(s.input, *prepared, false),
                             learn::check_input_options(*prepared, inputs), learn::check_final_fit(classifier, s.options),
                             learn::check_tunable(*prepared, s.options)})
        if (!st) {
            std::fprintf(stderr, "rollsense %s: %s\n", command, st.error().describe().c_str());
            return kExitUsage;
        }
    auto loaded = learn::load_feature_rows(s.input, feature_settings_from_args(args));
    if (!loaded) {
        std::fprintf(stderr, "rollsense %s: %s\n", command, loaded.error().describe().c_str());
        return exit_code_for(loaded.error().code, kExitConfig);
    }
    rows = std::move(loaded).value();
    if (auto st = warn_unreadable_trials(rows); !st) {
        std::fprintf(stderr, "rollsense %s: %s\n", command, st.error().describe().c_str());
        return exit_code_for(st.code(), kExitConfig);
    }
    std::fprintf(stderr, "%s\n", learn::summarize_rejections(rows).c_str());
    return kExitOk;
}

namespace {

const char* kHelp = R"(usage: rollsense evaluate INPUT [options]

INPUT is a dataset folder (features are extracted with the paper's settings or
the feature options of 'rollsense features') or a features CSV.

A classifier that takes the prepared series (minirocket) reads the dataset's
three sensor channels through the series rule (docs/series-preparation.md);
it needs a dataset folder, and may be listed beside feature classifiers.

Reports, for the clean trials:
  * the classifier preset under repeated stratified k-fold CV: accuracy mean ±
    sd over repetitions, a 95 % Wilson interval on the pooled out-of-fold
    predictions, the confusion matrix and per-class true-positive rates;
  * with several classifiers (--classifier a,b): each one on the same folds,
    and per pair the per-fold accuracy differences (mean, sd, paired t, the
    Nadeau-Bengio corrected t, sign counts);
  * the paper's analyses (cylinder vs polygon, cylinders misclassified, base
    edge length among polygons, pentagon <-> hexagon) beside the paper's numbers;
  * with --optimize: the paper's protocol, Bayesian optimisation on ONE fixed
    partition (an optimistic figure, labelled so), and nested CV (tuning inside
    every outer training fold), the honest tuned figure.

options:
  --classifier LIST   classifier plugin (default {default_classifier}), or
                      several, comma-separated: each on the same folds; an
                      entry may carry its own parameters: NAME:KEY=VALUE
  --set KEY=VALUE     classifier parameter for every listed classifier,
                      repeatable (e.g. --set learners=100)
  --folds K           k of the k-fold CV (5)
  --repeats R         repetitions of the CV with different partitions (10)
  --seed S            partition and optimiser seed (default: the seed the
                      dataset was recorded with, so that the run's own
                      figures come out; 1 for a features CSV, a dataset
                      without one, or one recorded with --seed 0)
  --cv LIST           also cross-validate with whole groups held out, beside
                      random k-fold (always run): grouped (needs --group-by),
                      blocked (needs --block), comma-separated; figures in the
                      report and evaluation.json, in the order given
                      (docs/identification.md).
                      With --optimize each is also tuned on folds of its own
                      kind, built from each outer training fold's trials
  --group-by COLUMN   grouped CV: a manifest column (trial_id, object, speed,
                      repetition, mount, index_in_mount, or a key of its
                      extra column);
                      with no more groups than folds, leave one group out
                      (speed: a speed-transfer test)
  --block N           blocked CV: runs of N consecutive trials within a mount
                      are groups, so neighbouring rolls never straddle
                      training and test
  --trials SET        clean (default): the paper's clean trials, and with a
                      series classifier only those the series rule accepts
                      too (every classifier sees the same trials and folds);
                      all: every trial the series rule accepts, including
                      those the paper's peak rule refuses (series classifiers
                      only). Left-out trials and why: evaluation.json
  --series-amplitude MODE
                      series rule amplitude: global_scale or z_per_channel
                      (default: docs/series-preparation.md; series
                      classifiers only)
  --series-time-axis contact|roll_relative
                      series rule time axis: contact (default, the paper's
                      timing rule) or roll_relative, OUTSIDE THE PAPER'S
                      TIMING RULE: the whole recording is resampled, so the
                      traversal speed (a cylinder's diameter) is in the
                      series; for measuring that leak only, and every output
                      says so (series classifiers only)
  --prefixes          also identify before the roll ends: for f = 10 %, 20 %,
                      ... 100 % of the nominal roll on the contact's own
                      clock (from the first clear bump's half-way rise, in
                      units of its width; docs/identification.md), train on
                      the training folds' prefixes and test on the test fold's
                      (one k-fold per fraction unless --repeats is given);
                      a prefix without input (bagged trees: < 3 valid peaks)
                      counts as wrong, shown as "no decision". Curves per
                      classifier and speed in the report and evaluation.json
                      (docs/identification.md)
  --optimize          also run the Bayesian optimisation (classifier.md §3 search space)
  --evaluations N     with --optimize: optimiser evaluations (30)
  --no-nested         with --optimize: skip the nested CV (much faster, no honest tuned figure)
  -o, --output FILE   also write the report and evaluation.json, beside each
                      other: FILE.txt and FILE.json for -o FILE.json, else
                      FILE and FILE's stem + .json (schema: docs/evaluation-json.md)
  --plugin-path DIR   search classifier plugins here first (repeatable)
  -v, --verbose       debug messages;   -q, --quiet   no info messages: warnings, errors
  plus the feature options of 'rollsense features' when INPUT is a dataset
  (refused with a features CSV, whose features are computed already))";

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    const LearnSetup s = learn_setup_from_args(args, {"--optimize", "--no-nested", "--prefixes"}, {});
    setup_logging(args);
    warn_if_partial(s.input);
    const auto out = output_option(args);
    const auto files = learn::evaluation_files(out);
    if (!out.empty())
        if (int rc = check_output_files("evaluate", s.input, {files.text, files.json}); rc != kExitOk) return rc;
    runtime::PluginRegistry registry(runtime::PluginRegistry::default_search_path(s.plugin_path));
    learn::PipelineResult result;
    if (int rc = run_learning_pipeline("evaluate", args, s, registry, result, true); rc != kExitOk) return rc;
    std::fputs(learn::format_evaluation(result.evaluation).c_str(), stdout);  // evaluation.txt's text, nothing else
    if (!out.empty()) {
        if (auto st = learn::write_evaluation_files(result.evaluation, files); !st) {
            std::fprintf(stderr, "rollsense evaluate: %s\n", st.error().describe().c_str());
            return exit_code_for(st.code());
        }
    }
    return kExitOk;
}

const Registration reg{{"evaluate", "cross-validate a classifier on a dataset or features file",
                        learn::with_default_classifier(kHelp, share_dir()), &run}};

}  // namespace
}  // namespace rollsense::cli
