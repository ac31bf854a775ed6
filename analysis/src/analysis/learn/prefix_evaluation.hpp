// Accuracy against the share of the roll seen, for every classifier of an
// evaluation, on its trials and its folds. A prefix is the recording up to
// the contact's onset (series::contact_onset) plus fraction f of the nominal
// length after the onset at the trial's speed (f = 1: the whole recording),
// so that time runs from the contact, as the paper's timing rule asks. For each f the classifiers are trained on the
// training folds' prefixes and tested on the test fold's prefixes; a prefix
// the input step cannot use (features: fewer than three valid peaks; series:
// the series rule refuses it) gets no decision and counts as wrong.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "analysis/learn/pipeline.hpp"
#include "analysis/learn/prefix_curves.hpp"

namespace rollsense::learn {

// The samples a prefix at `fraction` keeps of a recording of `samples`
// samples whose contact was first seen at sample `onset`: the onset plus
// fraction × `nominal` (the speed's nominal length after the onset), never
// more than the recording has; fraction ≥ 1 keeps it all; a recording whose
// contact never began keeps nothing (no decision).
std::size_t prefix_samples(double fraction, std::optional<std::size_t> onset, double nominal, std::size_t samples);

// Where the prefixes of loaded trials end: each trial's onset, found on
// `channels` with `settings` (its min_amplitude), and per speed the nominal
// length after the onset (medians over the speed's trials that have one).
struct PrefixCuts {
    std::vector<std::optional<std::size_t>> onset;  // per trial
    std::vector<NominalLength> nominal;             // per speed, in ascending order
    std::vector<double> nominal_samples;            // per trial: its speed's nominal samples
    std::size_t keep(std::size_t trial, double fraction, std::size_t samples) const;
};
PrefixCuts prefix_cuts(const std::vector<TrialRecord>& records, const std::vector<TrialData>& data,
                       std::span<const std::size_t> channels, const series::SeriesSettings& settings);

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
