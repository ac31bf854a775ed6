// Accuracy against the share of the roll seen, for every classifier of an
// evaluation, on its trials and its folds. A prefix is the samples from
// record_start up to fraction f of the recording's nominal length at its speed
// (f = 1: the whole recording). For each f the classifiers are trained on the
// training folds' prefixes and tested on the test fold's prefixes; a prefix
// the input step cannot use (features: fewer than three valid peaks; series:
// the series rule refuses it) gets no decision and counts as wrong.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "analysis/learn/pipeline.hpp"
#include "analysis/learn/prefix_curves.hpp"

namespace rollsense::learn {

// The nominal length of each speed: medians over `trials` (loaded records).
std::vector<NominalLength> nominal_lengths(const std::vector<TrialRecord>& records,
                                           const std::vector<TrialData>& data);

// The curves of every classifier of `evaluation` (made by evaluate_prepared
// on the dataset at `dataset_dir`, with `inputs`): its trials, its partitions.
Result<PrefixCurves> prefix_curves(const std::filesystem::path& dataset_dir, const Evaluation& evaluation,
                                   const std::vector<PreparedClassifier>& classifiers,
                                   const features::FeatureSettings& feature_settings, const InputOptions& inputs,
                                   const PrefixOptions& options);

// Models for identification before the roll ends (scripts/examples/identify_early.lua):
// for each fraction, `classifier` (a series classifier) trained on the prefix of
// every trial of the dataset that the series rule accepts at that fraction.
struct PrefixModel {
    double fraction = 1.0;
    std::size_t trained = 0;  // prefixes trained on
    std::size_t refused = 0;  // prefixes the series rule refused (e.g. no contact yet)
    ClassifierPtr model;      // empty when the accepted prefixes show fewer than two objects
};
struct PrefixModels {
    std::vector<NominalLength> nominal;  // what the fractions are fractions of, per speed
    std::vector<PrefixModel> models;     // in the order of `fractions`
};
Result<PrefixModels> train_prefix_models(const std::filesystem::path& dataset_dir,
                                         const PreparedClassifier& classifier, const InputOptions& inputs,
                                         const std::vector<double>& fractions);

}  // namespace rollsense::learn
