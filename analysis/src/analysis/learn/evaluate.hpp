// The identification experiment's evaluation, as plain functions the CLI and
// the Lua bindings call: repeated stratified k-fold CV of a preset, the
// paper's tuning protocol (Bayesian optimisation on one fixed partition,
// optimistic and labelled so), nested CV for an unbiased tuned figure, and the
// paper's own analyses beside the paper's numbers.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/features.hpp"
#include "analysis/learn/bayes_opt.hpp"
#include "analysis/learn/cross_validation.hpp"
#include "analysis/learn/cv_scheme.hpp"
#include "analysis/learn/folds.hpp"
#include "analysis/learn/metrics.hpp"
#include "analysis/learn/paper_analysis.hpp"
#include "analysis/learn/prefix_curves.hpp"
#include "analysis/learn/tuning.hpp"

namespace rollsense::learn {

struct EvaluationOptions {
    int folds = 5;              // k of the stratified k-fold (the paper: 5)
    int repeats = 10;           // repetitions with different partitions (classifier.md §7)
    std::uint64_t seed = 1;     // partitions and optimiser
    ParamSet params;            // classifier parameters (empty = the plugin's defaults)
    bool optimize = false;      // run the paper's Bayesian optimisation as well
    bool nested = true;         // with optimize: nested CV for the honest tuned figure
    BayesOptOptions bayes;      // evaluations (30), seed points, ...
    SearchSpace space;          // empty = the one the classifier declares (Classifier::search_space)
    std::string classifier;     // the classifier's name, for messages
    // Optional group per trial id (session, rig state): grouped folds instead of stratified.
    std::function<std::string(const features::FeatureRow&)> group_of;
    // Run beside the k-fold above, on the same trials: grouped and blocked CV
    // (cv_scheme.hpp), each reported next to it.
    std::vector<CvScheme> schemes;
    std::vector<ObjectShape> catalogue = paper_objects();
    std::function<void(const std::string&)> progress;  // one line per step
    // Set from another thread or a signal handler (Ctrl-C): the work stops at
    // the next classifier it would train, with ErrorCode::cancelled. The
    // pipeline (run_pipeline) checks it; nullptr = never stopped.
    const std::atomic<bool>* stop = nullptr;
};

struct RepeatedCv {
    int folds = 0;
    int repeats = 0;
    std::vector<double> repeat_accuracy;  // one figure per repetition
    std::vector<double> fold_accuracy;    // every fold of every repetition
    double mean = 0.0, sd = 0.0;          // over repetitions
    Interval wilson;                      // of the pooled rate, over the trials (n = rows, not R x rows)
    std::size_t correct = 0, total = 0;   // pooled
    ConfusionMatrix confusion;            // pooled over repetitions
    std::vector<int> first_predicted;     // out-of-fold labels of the first repetition
    std::vector<std::vector<double>> first_scores;  // their class scores (one vector per table row)
};

// One classifier's evaluation. `name` is how the comparison calls it (the
// plugin, with its parameters when the same plugin is compared with itself).
struct EvaluationReport {
    std::string name;
    std::string input = "features";  // the input kind it was evaluated on (features | series)
    std::size_t trials = 0;
    std::size_t clean = 0;
    std::vector<std::string> classes;
    ParamSet params;
    SearchSpace space;
    RepeatedCv baseline;
    struct SchemeCv {
        CvScheme scheme;
        RepeatedCv cv;
        // With optimize: the tuning under this scheme, its tuning folds by the
        // same groups (tuning.hpp): the fixed-partition figure and nested CV.
        std::optional<TunedCv> tuned;
        std::optional<NestedCv> nested;
    };
    std::vector<SchemeCv> scheme_cv;  // one per Evaluation::schemes, same order
    PaperAnalysis analysis;  // of the baseline's first repetition (one k-fold CV, as the paper)
    std::optional<TunedCv> tuned;
    std::optional<NestedCv> nested;
    double seconds = 0.0;
};

// A classifier to evaluate: its name in the results, how to make it, its parameters.
struct ClassifierRequest {
    std::string name;
    ClassifierFactory factory;
    ParamSet params;
    std::size_t table = 0;  // which of InputTables::tables it takes (evaluate_tables)
};

// A trial the input step left out, and why (features: the rejection reason).
struct RefusedTrial {
    std::string trial_id;
    std::string reason;
};

// A grouped or blocked CV's partitions, shared by every classifier.
struct SchemePlan {
    CvScheme scheme;
    FoldPlan plan;
    std::size_t groups = 0;  // distinct groups among the used trials
    std::vector<std::string> group_of;  // per used trial (table row): its group, for the tuning folds
};

// Between two classifiers of the comparison: their per-fold accuracies over
// every fold of every repetition, paired (same folds), a − b.
struct PairedComparison {
    std::size_t a = 0, b = 0;  // indices into Evaluation::classifiers
    PairedDifference difference;
};

// Several classifiers evaluated on the same input table and the same folds.
// With one classifier this is exactly the single evaluation of the past.
struct Evaluation {
    std::string input = "features";  // the input steps that made the tables: features | series | features+series
    std::string selection = "paper_clean";  // which trials: paper_clean | series_accepted (InputTables)
    std::string series_time_axis;  // with a series classifier: the series rule's time axis (InputTables)
    std::size_t trials = 0, clean = 0;
    std::vector<std::string> classes;
    std::vector<std::string> trial_ids;  // the table's rows: the trials used, in fold-assignment order
    std::vector<int> truth;              // their true labels (indices into classes)
    std::vector<char> peak_clean;        // per used trial: does the paper's peak rule keep it?
    std::vector<RefusedTrial> refused;   // trials the input step left out
    FoldPlan plan;                       // the partitions every classifier was scored on
    std::vector<SchemePlan> schemes;     // grouped / blocked CV beside it (EvaluationOptions::schemes)
    std::vector<EvaluationReport> classifiers;
    std::vector<PairedComparison> paired;  // every pair (i < j), i − j
    std::optional<PrefixCurves> prefixes;  // identification before the roll ends (--prefixes)
    double seconds = 0.0;
    const EvaluationReport& primary() const { return classifiers.front(); }
};

// The repetitions run on `threads` threads (0 = all cores); the result does not depend on it.
Result<RepeatedCv> repeated_cv(const FeatureTable& table, const ClassifierFactory& factory, const ParamSet& params,
                               const FoldPlan& plan, unsigned threads = 0);
Result<RepeatedCv> repeated_cv(const FeatureTable& table, const ClassifierFactory& factory, const ParamSet& params,
                               int folds, int repeats, std::uint64_t seed,
                               const std::vector<std::string>* groups = nullptr);

// The input of one evaluation: one table per input kind, all holding the SAME
// trials in the SAME order with the SAME labels (so one fold plan, made from
// those labels, is every classifier's), table row i being rows[row_of[i]].
struct InputTables {
    std::vector<FeatureTable> tables;
    std::vector<std::string> kinds;      // per table: "features" | "series"
    std::vector<std::size_t> row_of;     // table row → index into rows
    std::vector<RefusedTrial> refused;   // trials left out, with why; empty = rows' rejection reasons
    std::string selection = "paper_clean";
    std::string series_time_axis;        // with a series table: contact | roll_relative (series::to_string)
};

// Every classifier on its table (ClassifierRequest::table), all on one fold
// plan made from options.folds / repeats / seed / group_of. Tables that differ
// in rows or labels are an error: a paired comparison needs the same trials.
Result<Evaluation> evaluate_tables(const std::vector<features::FeatureRow>& rows, const InputTables& input,
                                   const std::vector<ClassifierRequest>& classifiers,
                                   const EvaluationOptions& options);

// One table for every classifier (its rows are rows[row_of[i]]).
Result<Evaluation> evaluate_table(const std::vector<features::FeatureRow>& rows, const FeatureTable& table,
                                  const std::vector<std::size_t>& row_of,
                                  const std::vector<ClassifierRequest>& classifiers,
                                  const EvaluationOptions& options);

// The feature table of the clean rows, then evaluate_table(): the learning
// pipeline (analysis/pipeline.hpp) chooses the input step; this is the one
// for feature-vector classifiers.
Result<Evaluation> evaluate_features(const std::vector<features::FeatureRow>& rows,
                                     const std::vector<ClassifierRequest>& classifiers,
                                     const EvaluationOptions& options);

// One classifier with options.params (kept for tests and simple callers).
Result<EvaluationReport> evaluate(const std::vector<features::FeatureRow>& rows, const ClassifierFactory& factory,
                                  const EvaluationOptions& options);

// The model to deploy: trained on every clean trial, with `options.params`, or
// — with options.optimize — with the parameters the paper's protocol picks,
// on tuning folds that follow options.schemes (at most one; none: random
// stratified, the paper's).
struct FinalModel {
    ClassifierPtr classifier;
    ParamSet params;
    std::optional<BayesOptResult> search;
    std::string tuning_folds;  // with optimize: "5-fold, random stratified", "3-fold, grouped by speed"
};
// Ok when `table` holds trials of two classes or more, what `task` ("evaluation", "training") needs; else
// why not, naming the one class there is and the way out (review: train made a one-class model of one trial).
Status check_two_classes(const FeatureTable& table, const char* task);
// Whether fit_final can tune with `options`, known before any work: its
// tuning folds follow at most one scheme.
Status check_final_tuning(const EvaluationOptions& options);
// The fold options that the trials read cannot take, known once they are read
// and selected (`used` of `rows`) and before any training: more folds than
// used trials, or a grouped scheme's column the trials lack. Each names the
// option, what the trials have and the way out. The commands take these as
// their command line's error (exit 2); rs.analyse raises them as before.
// With fewer than 2 used trials it passes: the evaluation names what is missing.
Status check_fold_options(const std::vector<features::FeatureRow>& rows, std::size_t used,
                          const EvaluationOptions& options);
Result<FinalModel> fit_final(const std::vector<features::FeatureRow>& rows, const ClassifierFactory& factory,
                             const EvaluationOptions& options);

// How a classifier did, out of fold in the first repetition, on the used
// trials that the paper's peak rule refuses (with trials=all; 0 otherwise).
struct SubsetScore {
    std::size_t total = 0, correct = 0;
};
SubsetScore paper_refused_first_repeat(const Evaluation& evaluation, const EvaluationReport& classifier);

// The label of every result made with the series time axis roll_relative.
inline constexpr const char* kOutsideTimingRule = "outside the paper's timing rule";
// With time axis roll_relative, the caveat every output of `evaluation` carries
// (text, evaluation.json, report); empty otherwise.
std::string time_axis_caveat(const Evaluation& evaluation);

// Human-readable report: every figure labelled with how it was obtained.
// `with_timing` = false leaves out the final "evaluation took" line.
std::string format_report(const EvaluationReport& report, bool with_timing = true);
// What the count of trials used is called: "clean" (the paper's rule), or "used" when the evaluation took trials the
// paper's rule refuses (--trials all), whose count is no clean count (review: "clean 1246" beside the paper
// analyses' "clean 1176 of 1350").
const char* used_trials_word(const Evaluation& evaluation);
// With a series classifier, which trials were used, and how each classifier did on those the paper's peak rule
// refuses (lines of text, each ending in '\n'); empty for features alone (the paper's clean trials, as always said).
std::string selection_line(const Evaluation& evaluation);
// evaluation.txt: one classifier exactly as format_report(); several: each
// one's report under its name, then the paired comparison.
std::string format_evaluation(const Evaluation& evaluation);

}  // namespace rollsense::learn
