// Classifier-agnostic cross-validation. A classifier is made by a factory from
// a parameter set, so the same code evaluates a plugin created through the
// kernel's registry, a core library linked directly in a test, or anything else
// implementing rollsense::Classifier.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "rollsense/classifier.hpp"
#include "rollsense/params.hpp"

namespace rollsense::learn {

// shared_ptr so that a kernel handle (which pins the plugin's library) can be
// the owner behind an aliasing pointer to its Classifier.
using ClassifierPtr = std::shared_ptr<Classifier>;
// Makes a configured, untrained classifier. `params` are raw values: keys the
// optimiser or the user set; the factory fills defaults and validates them.
// Called from several threads at once (repeated_cv runs repetitions in parallel).
using ClassifierFactory = std::function<Result<ClassifierPtr>(const ParamSet& params)>;

// The rows `rows` of `table`, keeping every class name (so labels stay valid).
FeatureTable subset(const FeatureTable& table, std::span<const std::size_t> rows);

// Train. A plugin's exceptions are errors naming it (checked_classifier).
Result<ClassifierPtr> train_classifier(const FeatureTable& table, const ClassifierFactory& factory,
                                       const ParamSet& params);
// Predictions (label and per-class scores) for table rows `rows`; predictions
// check_prediction refuses turned into errors.
Result<std::vector<Prediction>> predict_rows(const Classifier& c, const FeatureTable& table,
                                             std::span<const std::size_t> rows);
// Labels only, for table rows `rows`.
Result<std::vector<int>> predict_labels(const Classifier& c, const FeatureTable& table,
                                        std::span<const std::size_t> rows);

struct CvResult {
    std::vector<int> predicted;           // out-of-fold label per table row
    std::vector<std::vector<double>> scores;  // out-of-fold class scores per table row
    std::vector<double> fold_accuracy;    // per fold
    std::size_t correct = 0;
    double accuracy() const { return predicted.empty() ? 0.0 : static_cast<double>(correct) / static_cast<double>(predicted.size()); }
};

// k-fold cross-validation on a given partition (fold[i] in [0, k)).
Result<CvResult> cross_validate(const FeatureTable& table, std::span<const int> folds, int k,
                                const ClassifierFactory& factory, const ParamSet& params);

}  // namespace rollsense::learn
