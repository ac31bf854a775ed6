// The paper's Fig. 8 on one of this dataset's trials: the 13 features drawn on
// the smoothed peaks they come from — amplitude (F1–F3), peak width and its
// mid-point against the maximum (skewness F4–F6, widths F10–F11), half-width
// (F7–F9) and the time between maxima (F12–F13).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/features.hpp"
#include "analysis/learn/paper_analysis.hpp"
#include "analysis/report/plotted_trial.hpp"

namespace rollsense::report {

// The trial to draw: a clean trial of the first object in display order
// (a cylinder in the paper's set: its peaks are the clearest), at the middle
// speed, lowest repetition. Manifest index, or nothing if no trial is clean.
std::optional<std::size_t> pick_feature_trial(const DatasetReader& dataset,
                                              const std::vector<features::FeatureRow>& rows,
                                              const std::vector<learn::ObjectShape>& catalogue);

std::string feature_figure(const PlottedTrial& trial, const std::string& id);

// The trial's 13 feature values with their meaning, as an HTML table.
std::string feature_values_table(const PlottedTrial& trial);

}  // namespace rollsense::report
