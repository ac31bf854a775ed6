// Accuracy against the share of the roll seen, for every classifier of an
// evaluation, on its trials and its folds. A prefix is cut on the contact's
// own clock (series::contact_clock): the recording up to the onset plus
// fraction f of the nominal roll after it at the trial's speed, counted in the
// trial's unit (f = 1: the whole recording), so that timing is relative to the
// contact, as the paper's rule asks. For each f the classifiers are trained on
// the training folds' prefixes and tested on the test fold's prefixes; a prefix
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
#include "analysis/series/onset.hpp"

namespace rollsense::learn {

// The samples a prefix at `fraction` keeps of a recording of `samples`
// samples with contact clock `clock`: the onset plus fraction ×
// `nominal_units` (the speed's nominal roll after the onset, in units) × the
// trial's unit, and at least up to the sample that shows the unit (before it
// a live run cannot place the cut); never more than the recording has.
// fraction ≥ 1 keeps it all; a recording without a unit keeps nothing (no decision).
std::size_t prefix_samples(double fraction, const std::optional<series::ContactClock>& clock, double nominal_units,
                           std::size_t samples);

// Where the prefixes of loaded trials end: each trial's contact clock, found
// on `channels` with `settings` (its min_amplitude), and per speed the nominal
// roll after the onset (medians over the speed's trials that have a unit).
struct PrefixCuts {
    std::vector<std::optional<series::ContactClock>> clock;  // per trial
    std::vector<NominalLength> nominal;                      // per speed, in ascending order
    std::vector<double> nominal_units;                       // per trial: its speed's nominal units
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
