// Accuracy against the share of the roll seen, for every classifier of an
// evaluation, on its trials and its folds. A prefix is cut on the contact's
// own clock (series/contact_clock.hpp): the recording up to fraction f of the
// nominal roll, counted in the trial's clock units from the clock's zero
// (f = 1: the whole recording), so that timing is relative to the contact, as
// the paper's rule asks. For each f the classifiers are trained on the
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
#include "analysis/series/contact_clock.hpp"

namespace rollsense::learn {

// The samples a prefix at `fraction` keeps of a recording of `samples`
// samples with clock `clock`: the fewest whose series::clock_progress (with a
// nominal roll of `units`) reaches `fraction`, and at least up to the sample
// that showed the clock (before it a live run cannot place the cut); never
// more than the recording has. fraction ≥ 1 keeps it all; a recording without
// a clock keeps nothing (no decision).
std::size_t prefix_samples(double fraction, const std::optional<series::ContactClock>& clock, double units,
                           std::size_t samples);

// Where the prefixes of loaded trials end: each trial's clock, found on
// `channels`, and the nominal roll in clock units (the median over the trials
// with a clock of the roll from the clock's zero to the recording's end: one
// figure for every speed, since the clock's unit already scales with it).
struct PrefixCuts {
    std::vector<std::optional<series::ContactClock>> clock;  // per trial
    double units = 0.0;
    std::vector<NominalLength> nominal;                      // per speed, for reading the curves
    std::size_t keep(std::size_t trial, double fraction, std::size_t samples) const;
    // SeriesSettings::prefix for that cut (0: the whole recording).
    std::size_t series_prefix(std::size_t trial, double fraction, std::size_t samples) const;
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
    double units = 0.0;                  // the nominal roll in clock units: what the fractions are fractions of
    std::vector<NominalLength> nominal;  // per speed, for reading
    std::vector<PrefixModel> models;     // in the order of `fractions`
};
Result<PrefixModels> train_prefix_models(const std::filesystem::path& dataset_dir,
                                         const PreparedClassifier& classifier, const InputOptions& inputs,
                                         const std::vector<double>& fractions);

}  // namespace rollsense::learn
