// Bayesian hyperparameter optimisation in the manner of MATLAB's bayesopt as
// Classification Learner uses it: a Gaussian-process surrogate (ARD-free
// Matérn 5/2 kernel on the unit cube, hyperparameters chosen by marginal
// likelihood), a few random seed points, then expected improvement; the answer
// is the visited point with the lowest upper confidence bound of the modelled
// objective (MATLAB's 'min-visited-upper-confidence-interval'), which is less
// fooled by one lucky evaluation than the raw minimum.
//
// Not reproduced: MATLAB's "per second" acquisition (it trades error against
// fit time); plain EI is used, so the figure does not depend on machine speed.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/learn/cross_validation.hpp"
#include "rollsense/classifier.hpp"
#include "rollsense/params.hpp"
#include "rollsense/status.hpp"

namespace rollsense::learn {

// The space is declared by the classifier (rollsense/classifier.hpp).
using rollsense::SearchDimension;
using rollsense::SearchSpace;

struct BayesOptOptions {
    int evaluations = 30;     // MATLAB MaxObjectiveEvaluations
    int seed_points = 4;      // random points before the surrogate decides (MATLAB NumSeedPoints)
    int candidates = 3000;    // random acquisition candidates per step (plus local ones near the best)
    double exploration = 0.01;  // EI margin ξ in standardised objective units
    std::uint64_t seed = 1;
    // Called after every evaluation: (index, params, objective).
    std::function<void(int, const ParamSet&, double)> progress;
};

struct BayesOptEvaluation {
    ParamSet params;
    double objective = 0.0;
};

struct BayesOptResult {
    std::vector<BayesOptEvaluation> history;
    std::size_t best = 0;             // index into history
    double best_predicted = 0.0;      // surrogate mean at the best point
    const ParamSet& best_params() const { return history[best].params; }
    double best_objective() const { return history[best].objective; }
};

using Objective = std::function<Result<double>(const ParamSet& params)>;

// Minimises `objective` over `space`. `fixed` holds parameters that are not
// searched (seed, threads, ...); they are passed with every evaluation.
Result<BayesOptResult> bayes_optimize(const SearchSpace& space, const Objective& objective,
                                      const ParamSet& fixed, const BayesOptOptions& options);

// The space tuning searches on a table of `rows` trials × `cols` columns:
// `given` when not empty (a test's or a caller's own), else what one
// classifier made by `factory` with `params` declares (Classifier::search_space;
// it may be empty: nothing to tune).
Result<SearchSpace> declared_search_space(const ClassifierFactory& factory, const ParamSet& params, std::size_t rows,
                                          std::size_t cols, const SearchSpace& given = {});
// The shape a space is asked for before the data is read (the stock run's 1,164 clean trials of 13 features): its
// ranges may depend on the shape, the parameters it names should not.
inline constexpr std::size_t kProbeRows = 1164, kProbeCols = 13;
// The same, for tuning: an empty space is an error naming `classifier`.
Result<SearchSpace> tuning_space(const ClassifierFactory& factory, const ParamSet& params, std::size_t rows,
                                 std::size_t cols, const SearchSpace& given, const std::string& classifier);

// "learners=123 min_leaf_size=2 ..." for reports: the values of `params` that
// `space` searches, in its order (optimiser progress, chosen parameters).
std::string describe_params(const ParamSet& params, const SearchSpace& space);
// Every value of `params` in key order, the same way: what evaluation.json's
// "parameters" holds, for the text evaluation and `rollsense train`.
std::string describe_param_values(const ParamSet& params);

}  // namespace rollsense::learn
