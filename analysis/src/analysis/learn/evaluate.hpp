// The identification experiment's evaluation, as plain functions the CLI and
// the Lua bindings call: repeated stratified k-fold CV of a preset, the
// paper's tuning protocol (Bayesian optimisation on one fixed partition,
// optimistic and labelled so), nested CV for an unbiased tuned figure, and the
// paper's own analyses beside the paper's numbers.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/features.hpp"
#include "analysis/learn/bayes_opt.hpp"
#include "analysis/learn/cross_validation.hpp"
#include "analysis/learn/metrics.hpp"
#include "analysis/learn/paper_analysis.hpp"

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
    std::vector<ObjectShape> catalogue = paper_objects();
    std::function<void(const std::string&)> progress;  // one line per step
};

struct RepeatedCv {
    int folds = 0;
    int repeats = 0;
    std::vector<double> repeat_accuracy;  // one figure per repetition
    std::vector<double> fold_accuracy;    // every fold of every repetition
    double mean = 0.0, sd = 0.0;          // over repetitions
    Interval wilson;                      // pooled over all out-of-fold predictions
    std::size_t correct = 0, total = 0;   // pooled
    ConfusionMatrix confusion;            // pooled over repetitions
    std::vector<int> first_predicted;     // out-of-fold labels of the first repetition
};

struct TunedCv {
    BayesOptResult search;
    double same_folds_accuracy = 0.0;  // 1 − objective at the chosen point: tuned and scored on the same folds
    ConfusionMatrix confusion;
};

struct NestedCv {
    std::vector<double> outer_accuracy;
    std::vector<ParamSet> chosen;  // per outer fold
    double mean = 0.0, sd = 0.0;
    Interval wilson;
    std::size_t correct = 0, total = 0;
    ConfusionMatrix confusion;
};

struct EvaluationReport {
    std::size_t trials = 0;
    std::size_t clean = 0;
    std::vector<std::string> classes;
    ParamSet params;
    SearchSpace space;
    RepeatedCv baseline;
    PaperAnalysis analysis;  // of the baseline's first repetition (one k-fold CV, as the paper)
    std::optional<TunedCv> tuned;
    std::optional<NestedCv> nested;
    double seconds = 0.0;
};

Result<RepeatedCv> repeated_cv(const FeatureTable& table, const ClassifierFactory& factory, const ParamSet& params,
                               int folds, int repeats, std::uint64_t seed,
                               const std::vector<std::string>* groups = nullptr);

Result<EvaluationReport> evaluate(const std::vector<features::FeatureRow>& rows, const ClassifierFactory& factory,
                                  const EvaluationOptions& options);

// The model to deploy: trained on every clean trial, with `options.params`, or
// — with options.optimize — with the parameters the paper's protocol picks.
struct FinalModel {
    ClassifierPtr classifier;
    ParamSet params;
    std::optional<BayesOptResult> search;
};
Result<FinalModel> fit_final(const std::vector<features::FeatureRow>& rows, const ClassifierFactory& factory,
                             const EvaluationOptions& options);

// Human-readable report: every figure labelled with how it was obtained.
std::string format_report(const EvaluationReport& report);

}  // namespace rollsense::learn
