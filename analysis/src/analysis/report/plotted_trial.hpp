// One recorded trial made ready to draw: its three smoothed channels on the
// feature pipeline's time base, and the peaks and features extracted from
// them, so a figure shows exactly what the classifier was given.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/features.hpp"
#include "rollsense/status.hpp"

namespace rollsense::report {

struct PlottedTrial {
    TrialInfo info;
    std::vector<double> x;  // per sample: index (TimeBase::samples) or recorded time
    std::array<std::vector<double>, features::kChannels> smoothed;
    features::TrialFeatures features;
    std::string x_label;  // the x axis with its unit: "time (samples)" or "time (s)"
    std::string y_label;  // the reading with its unit (dataset-info.csv channel_units)
};

Result<PlottedTrial> load_plotted_trial(const DatasetReader& dataset, const TrialRecord& record,
                                        const features::FeatureSettings& settings);

// The first and last sample index at or above half the channel's maximum
// inside its peak (the half-width's extent, outermost rule), for drawing.
std::pair<std::size_t, std::size_t> half_maximum_span(const std::vector<double>& smoothed,
                                                      const features::ChannelPeak& peak);

}  // namespace rollsense::report
