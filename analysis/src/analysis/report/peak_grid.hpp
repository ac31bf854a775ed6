// The paper's Fig. 7 for any dataset: smoothed peaks of the three channels of
// selected trials on a normalised time axis, one row per object (in the
// confusion matrix's order), one column per rolling speed.
#pragma once

#include <string>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/features.hpp"
#include "analysis/learn/paper_analysis.hpp"

namespace rollsense::report {

// Which trial stands for (object, speed): the clean trial with the lowest
// repetition, or, when none is clean, the first trial, drawn as rejected.
// Returns manifest indices, rows in display order, columns in speed order.
struct TrialSelection {
    std::vector<std::string> objects;  // display order
    std::vector<std::string> speeds;   // ascending (numerically when numbers)
    std::vector<std::vector<long>> trial;  // [object][speed] manifest index, −1 if none recorded
};
TrialSelection select_trials(const DatasetReader& dataset, const std::vector<features::FeatureRow>& rows,
                             const std::vector<learn::ObjectShape>& catalogue);

// Speed labels in ascending order: numerically when every label is a number.
std::vector<std::string> sorted_speeds(std::vector<std::string> speeds);

Result<std::string> peak_grid_figure(const DatasetReader& dataset, const TrialSelection& selection,
                                     const features::FeatureSettings& settings, const std::string& id);

// Colours of ch1..ch3, shared by every trial figure and its legend.
const char* channel_colour(std::size_t channel);

}  // namespace rollsense::report
