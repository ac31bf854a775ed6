// Every choice the paper leaves open (method.md "Decision"s) as a documented
// setting whose default is the paper-faithful one.
#pragma once

#include <string>

#include "rollsense/params.hpp"
#include "rollsense/status.hpp"

namespace rollsense::features {

enum class WindowScope {
    per_channel,  // default: each channel gets the window its own spectrum asks for
    shared,       // one window from the 3-channel matrix, as smoothdata(X) on an N×3 matrix
};

enum class HalfWidthRule {
    outermost,   // default: first to last sample ≥ 50 % inside the peak (FWHM of the envelope)
    contiguous,  // walk out from the maximum until the reading drops below 50 %
};

enum class TimeBase {
    samples,     // default: time in sample indices (only ratios survive, as in the paper)
    timestamps,  // the recorded time column (differs only if sampling jittered)
};

struct FeatureSettings {
    double smoothing_factor = 0.05;  // MATLAB SmoothingFactor
    int smoothing_window = 0;        // > 0: fixed window, overrides the factor (0 = MATLAB's heuristic)
    WindowScope window_scope = WindowScope::per_channel;
    double peak_fraction = 0.05;     // the peak ends where the reading drops below this fraction of its max
    double min_amplitude = 0.01;     // a valid peak's maximum must exceed this (post-filter noise ≈ ±0.005)
    bool require_complete_peak = true;  // Decision: both walks must end inside the series
    HalfWidthRule half_width = HalfWidthRule::outermost;
    TimeBase time_base = TimeBase::samples;
    bool interpolate_crossings = false;  // sub-sample 5 % / 50 % crossings (linear); off = paper's definition

    bool operator==(const FeatureSettings&) const = default;
};

// The longest fixed window (samples): longer than any recording, and an int
// whatever the platform.
inline constexpr int kMaxSmoothingWindow = 10000;

// The settings as a parameter schema (for profiles, Lua and the CLI) and back.
// feature_settings_from is the one check of the values: smoothing_factor in
// [0, 1], smoothing_window in [0, kMaxSmoothingWindow], peak_fraction in (0, 1),
// min_amplitude finite and >= 0 (NaN refused); the error names the setting
// first ("peak_fraction must be ...").
ParamSchema feature_settings_schema();
Result<FeatureSettings> feature_settings_from(const ParamSet& params);
ParamSet to_params(const FeatureSettings& settings);

std::string_view to_string(WindowScope scope) noexcept;
std::string_view to_string(HalfWidthRule rule) noexcept;
std::string_view to_string(TimeBase base) noexcept;

}  // namespace rollsense::features
