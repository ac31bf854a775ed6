#include "rollsense/features/settings.hpp"

#include <cmath>

#include "rollsense/csv.hpp"

namespace rollsense::features {

std::string_view to_string(WindowScope scope) noexcept {
    return scope == WindowScope::shared ? "shared" : "per_channel";
}
std::string_view to_string(HalfWidthRule rule) noexcept {
    return rule == HalfWidthRule::contiguous ? "contiguous" : "outermost";
}
std::string_view to_string(TimeBase base) noexcept { return base == TimeBase::timestamps ? "timestamps" : "samples"; }

ParamSchema feature_settings_schema() {
    const FeatureSettings d;
    return {
        param_number("smoothing_factor", d.smoothing_factor,
                     "MATLAB smoothdata 'SmoothingFactor' (window chosen from each series' spectrum)", 0.0, 1.0),
        param_int("smoothing_window", d.smoothing_window,
                  "fixed Gaussian window in samples; 0 = derive it from the data like MATLAB", 0, kMaxSmoothingWindow,
                  "samples"),
        param_string("window_scope", std::string(to_string(d.window_scope)),
                     "compute the window per channel or once from the 3-channel matrix", {"per_channel", "shared"}),
        param_number("peak_fraction", d.peak_fraction, "a peak extends while the reading is >= this fraction of its max",
                     0.0, 1.0),
        param_number("min_amplitude", d.min_amplitude, "a valid peak's maximum must exceed this reading", 0.0),
        param_bool("require_complete_peak", d.require_complete_peak,
                   "reject a peak cut off by the start or end of the recording"),
        param_string("half_width", std::string(to_string(d.half_width)),
                     "half-width between the outermost 50 % crossings or the ones contiguous with the max",
                     {"outermost", "contiguous"}),
        param_string("time_base", std::string(to_string(d.time_base)),
                     "measure times in sample indices or with the recorded time column", {"samples", "timestamps"}),
        param_bool("interpolate_crossings", d.interpolate_crossings,
                   "linear sub-sample interpolation of the 5 % and 50 % crossings"),
    };
}

namespace {
Error refused(const char* setting, const char* range, double value) {
    return {ErrorCode::invalid_argument,
            std::string(setting) + " must be " + range + ", got " + csv::format_number(value)};
}
}  // namespace

Result<FeatureSettings> feature_settings_from(const ParamSet& p) {
    try {
        FeatureSettings s;
        if (p.has("smoothing_factor")) s.smoothing_factor = p.get_number("smoothing_factor");
        if (p.has("smoothing_window")) {
            const auto w = p.get_int("smoothing_window");
            if (w < 0 || w > kMaxSmoothingWindow)
                return Error{ErrorCode::invalid_argument, "smoothing_window must be a whole number of samples from 0 "
                                                          "(MATLAB's heuristic) to " +
                                                              std::to_string(kMaxSmoothingWindow) + ", got " +
                                                              std::to_string(w)};
            s.smoothing_window = static_cast<int>(w);
        }
        if (p.has("window_scope"))
            s.window_scope = p.get_string("window_scope") == "shared" ? WindowScope::shared : WindowScope::per_channel;
        if (p.has("peak_fraction")) s.peak_fraction = p.get_number("peak_fraction");
        if (p.has("min_amplitude")) s.min_amplitude = p.get_number("min_amplitude");
        if (p.has("require_complete_peak")) s.require_complete_peak = p.get_bool("require_complete_peak");
        if (p.has("half_width"))
            s.half_width = p.get_string("half_width") == "contiguous" ? HalfWidthRule::contiguous
                                                                      : HalfWidthRule::outermost;
        if (p.has("time_base"))
            s.time_base = p.get_string("time_base") == "timestamps" ? TimeBase::timestamps : TimeBase::samples;
        if (p.has("interpolate_crossings")) s.interpolate_crossings = p.get_bool("interpolate_crossings");
        // Written so that NaN fails every check: it would compare false with
        // every reading and reject (or keep) every peak.
        if (!(s.smoothing_factor >= 0.0 && s.smoothing_factor <= 1.0))
            return refused("smoothing_factor", "a number within [0, 1]", s.smoothing_factor);
        if (!(s.peak_fraction > 0.0 && s.peak_fraction < 1.0))
            return refused("peak_fraction", "a number within (0, 1)", s.peak_fraction);
        if (!(s.min_amplitude >= 0.0 && std::isfinite(s.min_amplitude)))
            return refused("min_amplitude", "a finite number >= 0", s.min_amplitude);
        return s;
    } catch (const StatusError& e) {
        return e.status();
    }
}

ParamSet to_params(const FeatureSettings& s) {
    ParamSet p;
    p.set("smoothing_factor", s.smoothing_factor);
    p.set("smoothing_window", std::int64_t{s.smoothing_window});
    p.set("window_scope", std::string(to_string(s.window_scope)));
    p.set("peak_fraction", s.peak_fraction);
    p.set("min_amplitude", s.min_amplitude);
    p.set("require_complete_peak", s.require_complete_peak);
    p.set("half_width", std::string(to_string(s.half_width)));
    p.set("time_base", std::string(to_string(s.time_base)));
    p.set("interpolate_crossings", s.interpolate_crossings);
    return p;
}

}  // namespace rollsense::features
