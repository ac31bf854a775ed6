// A private, minimal copy of the paper's smoothing, peak and validity rule
// (method.md §4, classifier.md §1) for the calibration bench only.
//
// Why private: the SDK's feature pipeline (rollsense/features.hpp) was being
// written at the same time as this bench; calibrating against a moving target
// would have been worse. Same definitions: MATLAB smoothdata 'gaussian' with
// SmoothingFactor 0.05 per channel, walk from the maximum to 5 %, valid if
// max > 0.01 and both walks end inside the series; 13 features as in §4.5–4.7.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace rollsense::sim::bench {

std::vector<double> smoothdata_gaussian(const std::vector<double>& x, double factor = 0.05);
// MATLAB's window heuristic alone, and smoothing with a given window.
int smoothing_window(const std::vector<double>& x, double factor = 0.05);
std::vector<double> gaussian_smooth(const std::vector<double>& x, int window);

struct PeakInfo {
    int start = 0, end = 0, imax = 0;
    double amplitude = 0.0;
    bool complete_start = false, complete_end = false;
    bool above_threshold = false;
    double half_width = 0.0;
};

PeakInfo find_peak(const std::vector<double>& y, double fraction = 0.05, double min_amplitude = 0.01);

struct TrialVerdict {
    bool clean = false;
    std::string reason;  // empty when clean
    bool all_above_threshold = true;
    std::array<PeakInfo, 3> peaks{};
    std::array<double, 13> features{};
};

TrialVerdict judge_trial(const std::array<std::vector<double>, 3>& raw);

}  // namespace rollsense::sim::bench
