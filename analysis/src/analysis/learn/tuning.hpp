// Hyperparameter tuning inside an evaluation: the paper's protocol (Bayesian
// optimisation on one fixed partition, scored on the same folds: optimistic)
// and nested CV (tuning inside each outer training fold: the honest figure).
//
// The tuning folds follow the fold scheme of the evaluation they belong to:
// random stratified for random k-fold (the paper's), and for grouped or
// blocked CV (--cv) the same groups, built from the outer training trials
// only. Otherwise the optimiser's validation folds would share a mount or a
// block of neighbouring rolls with its training folds, and tuning would select
// the parameters that profit most from that leak.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "analysis/learn/bayes_opt.hpp"
#include "analysis/learn/cross_validation.hpp"
#include "analysis/learn/cv_scheme.hpp"
#include "analysis/learn/metrics.hpp"

namespace rollsense::learn {

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

// How tuning partitions trials.
struct TuningFoldRule {
    // nullptr: random — stratified k-fold, or grouped k-fold by `groups` when
    // they are given (EvaluationOptions::group_of). Else the scheme's folds by
    // `groups` (required): leave one group out with no more groups than folds.
    const CvScheme* scheme = nullptr;
    const std::vector<std::string>* groups = nullptr;  // per table row
    // "random stratified", "grouped by speed", ...: for reports.
    std::string describe() const;
};

// One partition of the table rows `rows` (indices into `labels` and the
// rule's groups), fold[i] for rows[i], by the rule: the tuning folds of a
// training set use its trials only. k is the fold count asked for; the
// result's may be smaller (leave one group out). A scheme whose groups cannot
// make the folds — fewer than 2 groups among the rows, or a class whose every
// trial falls in one fold — is an error naming it (make_scheme_plan): there is
// no silent fallback to random folds.
struct TuningFolds {
    std::vector<int> fold;
    int k = 0;
};
Result<TuningFolds> tuning_folds(const TuningFoldRule& rule, std::span<const int> labels,
                                 const std::vector<std::string>& class_names, std::span<const std::size_t> rows, int k,
                                 std::uint64_t seed);

// The optimiser's objective: the k-fold misclassification rate on `folds`
// (which must outlive it).
Objective tuning_objective(const FeatureTable& table, const TuningFolds& folds, const ClassifierFactory& factory);

// Nested CV's partitions: outer folds by the rule over every row (seed +
// 7919), and per outer fold the tuning folds of its training rows by the same
// rule (seed + 104729 + f; fold[i] for the i-th training row in table order).
// Cheap: made before any training, so that a scheme that cannot make them is
// refused before minutes of tuning.
struct NestedPartitions {
    TuningFolds outer;
    std::vector<TuningFolds> inner;  // per outer fold
};
Result<NestedPartitions> nested_partitions(const TuningFoldRule& rule, std::span<const int> labels,
                                           const std::vector<std::string>& class_names, int k, std::uint64_t seed);

// What tuning needs besides the table and the rule.
struct TuningSetup {
    ClassifierFactory factory;
    ParamSet params;            // the preset: fixed values, and the start of every point
    SearchSpace space;          // searched on the whole table (tune_fixed_partition)
    SearchSpace given_space;    // EvaluationOptions::space: empty = the classifier's own, per training table
    std::string classifier;     // for messages
    int folds = 5;
    std::uint64_t seed = 1;
    BayesOptOptions bayes;
    std::function<void(const std::string&)> say;  // progress lines (may be empty)
};

// Bayesian optimisation on one fixed partition of every table row (seed
// `setup.seed`): the partition and the search. The deployed model's tuning.
struct FixedSearch {
    TuningFolds folds;
    BayesOptResult search;
};
Result<FixedSearch> search_fixed_partition(const FeatureTable& table, const TuningFoldRule& rule,
                                           const TuningSetup& setup);

// The paper's protocol: search_fixed_partition, the figure scored on the same folds.
Result<TunedCv> tune_fixed_partition(const FeatureTable& table, const TuningFoldRule& rule, const TuningSetup& setup);

// Nested CV on nested_partitions(): tuning inside each outer training fold,
// scored on its test fold.
Result<NestedCv> nested_cv(const FeatureTable& table, const TuningFoldRule& rule, const TuningSetup& setup);

}  // namespace rollsense::learn
