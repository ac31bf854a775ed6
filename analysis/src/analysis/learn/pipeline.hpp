// The learning pipeline every evaluation runs — `rollsense evaluate`,
// `rollsense report` and rs.analyse alike:
//
//   classifiers  resolve every requested plugin, validate its parameters and
//                ask which input it takes, before any work
//   rows         the dataset's trials with the feature-extraction step's
//                settings (or a features CSV as it was written)
//   input tables the steps the classifiers' input() picks: features → the
//                trials' 13 features; series → prepare_series() on the
//                dataset's three sensor channels (docs/series-preparation.md).
//                One trial selection for all (default: the paper's clean
//                trials that the series rule also accepts), so every
//                classifier sees the same trials, labels and folds
//   evaluation   every classifier on the same folds, paired differences
//   outputs      evaluation.txt and evaluation.json from the one Evaluation
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/features.hpp"
#include "rollsense/features/recorded.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/series/prepare.hpp"
#include "runtime/plugin/plugin_registry.hpp"

namespace rollsense::learn {

// One entry of a classifier list: which plugin, with which parameters, and the
// name the results use for it.
struct ClassifierSpec {
    std::string name;
    std::string plugin;
    ParamSet params;
};

// "a,b:learners=10:min_leaf=2": comma-separated entries, each a plugin name
// optionally followed by ":KEY=VALUE" parameters. `common` (the --set values)
// apply to every entry, the entry's own ones on top. An entry's name is its
// text; a name given twice gets " #2", " #3".
Result<std::vector<ClassifierSpec>> parse_classifier_list(const std::string& text, const ParamSet& common = {});
// A spec's name from its plugin and own parameters (as parse_classifier_list names it).
std::string spec_name(const std::string& plugin, const ParamSet& own);
// Gives repeated names a " #2", " #3" suffix so every result can be told apart.
void make_names_unique(std::vector<ClassifierSpec>& specs);

struct PreparedClassifier {
    ClassifierSpec spec;
    ClassifierFactory factory;
    ClassifierInput input = ClassifierInput::features;
};


// Every spec's plugin found, its parameters accepted and its input known. An
// unknown plugin fails with the list of available classifier plugins.
Result<std::vector<PreparedClassifier>> prepare_classifiers(runtime::PluginRegistry& registry,
                                                            const std::vector<ClassifierSpec>& specs);

// Which trials an evaluation uses.
enum class TrialSelection {
    paper_clean,      // the paper's clean trials (peak rule), and with a series classifier
                      // only those the series rule accepts as well (default)
    series_accepted,  // every trial the series rule accepts, including those the peak
                      // rule refuses: series classifiers only
};
std::string_view to_string(TrialSelection t) noexcept;
// "clean" | "all" (also the names to_string gives); the error lists both.
Result<TrialSelection> parse_trial_selection(std::string_view text);
// "global_scale" | "z_per_channel"; the error lists both.
Result<series::Amplitude> parse_amplitude(std::string_view text);
// "contact" | "roll_relative" (outside the paper's timing rule, for comparison
// only: docs/series-preparation.md); the error lists both.
Result<series::TimeAxis> parse_time_axis(std::string_view text);

// How the input step prepares the trials.
struct InputOptions {
    series::SeriesSettings series;  // the series rule's settings (docs/series-preparation.md)
    TrialSelection trials = TrialSelection::paper_clean;
    unsigned threads = 0;           // series preparation threads (0 = all cores)
    // The user named the series rule's amplitude or time axis (--series-*, series_*), if only at its preset value: a
    // list of feature classifiers then refuses it rather than ignore it (review: the default's name passed in silence).
    bool amplitude_named = false, time_axis_named = false;
};

// The channels a series classifier reads: the three the 13 features read
// (features::identification_channels), by column name.
Result<std::vector<std::string>> series_channels(const DatasetInfo& info, const std::string& dataset);

// What the input step can do with `input` (a dataset folder or a features
// CSV), checked before any work: a series classifier and the prefix curves
// need the recorded trials, which a features CSV does not hold. The error
// names the input and the classifier (invalid_argument: a bad combination).
Status check_input_holds_trials(const std::filesystem::path& input, const std::vector<PreparedClassifier>& classifiers,
                                bool prefixes);

// The input step's options against the kinds of classifiers listed, before any work: the series rule's time axis and
// amplitude apply to series classifiers only, and trials=all to a list of series classifiers only
// (invalid_argument, naming the option and the way out).
Status check_input_options(const std::vector<ClassifierInput>& kinds, const InputOptions& options);
Status check_input_options(const std::vector<PreparedClassifier>& classifiers, const InputOptions& options);

// The input step for the classifiers' kinds: one table per kind present
// (features first), the same trials in the same order. `dataset_dir` is the
// input the rows came from (a features CSV, or empty, has no series to
// prepare: asking for series then is an error naming it). Trials left out
// carry every reason (peak rule and series rule).
Result<InputTables> make_input_tables(const std::vector<features::FeatureRow>& rows,
                                      const std::filesystem::path& dataset_dir,
                                      const std::vector<ClassifierInput>& kinds, const InputOptions& options);

// Input step, then every classifier on the same folds.
Result<Evaluation> evaluate_prepared(const std::vector<features::FeatureRow>& rows,
                                     const std::filesystem::path& dataset_dir,
                                     const std::vector<PreparedClassifier>& classifiers,
                                     const EvaluationOptions& options, const InputOptions& input = {});

// The seed a dataset is partitioned with when none is given: the seed it was recorded with (dataset-info.csv), the one
// its run's rs.analyse used, so that `evaluate DIR`, `report DIR` and rs.analyse{dataset = DIR} give the run's own
// figures; `fallback` for a features table and for a dataset recorded without a seed or with 0 (which also means none).
std::uint64_t recorded_partition_seed(const std::filesystem::path& input, std::uint64_t fallback);

// With options.optimize, that every classifier declares something to tune (tuning_space), known before any work
// (invalid_argument naming the classifier; a plugin's wrong space: plugin_error).
Status check_tunable(const std::vector<PreparedClassifier>& classifiers, const EvaluationOptions& options);

// Whether fit_final_prepared can fit `classifier` with `options`, known
// before any work (tuning is implemented for feature classifiers only).
Status check_final_fit(const PreparedClassifier& classifier, const EvaluationOptions& options);

// The model to deploy for one prepared classifier, trained on every trial the
// input step selects (features: fit_final's rules, with options.optimize;
// series: the trials' prepared series, as the evaluation prepares them). One
// home for `rollsense train` and rs.analyse's model, so both fit the same one.
Result<FinalModel> fit_final_prepared(const std::vector<features::FeatureRow>& rows,
                                      const std::filesystem::path& dataset_dir, const PreparedClassifier& classifier,
                                      const EvaluationOptions& options, const InputOptions& input = {});

struct PipelineRequest {
    std::filesystem::path input;          // dataset folder or features CSV
    features::FeatureSettings features;   // the feature-extraction step's settings
    std::vector<ClassifierSpec> classifiers;
    EvaluationOptions options;            // options.params is ignored: each spec has its own
    InputOptions inputs;                  // series preparation and trial selection
    std::optional<PrefixOptions> prefixes;  // also: accuracy before the roll ends (needs a dataset folder)
    // The input dataset's features this run took from memory, with `features`' settings (rs.analyse).
    const features::RecordedFeatures* recorded = nullptr;
};

struct PipelineResult {
    std::vector<features::FeatureRow> rows;
    std::vector<PreparedClassifier> classifiers;
    Evaluation evaluation;
};

// Where the pipeline stopped, so that commands can tell a wrong input or
// plugin (configuration) from an evaluation that failed. `request`: the
// request's parts do not go together (check_input_holds_trials), found
// before any work. `options`: the fold options do not fit the trials read
// (check_fold_options), found before any training.
enum class PipelineStage { classifiers, request, rows, options, evaluation };

// The whole pipeline. `on_rows` runs once the rows are read (print the
// rejection summary, write features.csv); its error stops the pipeline.
Result<PipelineResult> run_pipeline(runtime::PluginRegistry& registry, const PipelineRequest& request,
                                    const std::function<Status(const std::vector<features::FeatureRow>&)>& on_rows = {},
                                    PipelineStage* failed = nullptr);

// The text evaluation and evaluation.json an output name stands for, in the
// same folder with the same stem: "out/eval.json" → out/eval.txt and
// out/eval.json (the JSON where it was asked for); any other name is the text,
// with the JSON beside it ("out/eval.txt" → out/eval.json, "out/eval" → out/eval.json).
struct EvaluationFiles {
    std::filesystem::path text, json;
};
EvaluationFiles evaluation_files(const std::filesystem::path& output);
// Writes both (format_evaluation, evaluation_json), each atomically.
Status write_evaluation_files(const Evaluation& evaluation, const EvaluationFiles& files);

}  // namespace rollsense::learn
