// From three raw channels to a clean/rejected decision and 13 features
// (method.md §4). Every threshold and rule comes from FeatureSettings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "rollsense/features.hpp"

namespace rollsense::features {

const std::array<std::string, kFeatureCount>& feature_names() {
    static const std::array<std::string, kFeatureCount> names = {"F1", "F2", "F3",  "F4",  "F5",  "F6", "F7",
                                                                 "F8", "F9", "F10", "F11", "F12", "F13"};
    return names;
}

const std::array<std::string, kFeatureCount>& feature_descriptions() {
    static const std::array<std::string, kFeatureCount> d = {
        "amplitude of channel 1",
        "amplitude of channel 2",
        "amplitude of channel 3",
        "skewness of channel 1: (peak mid-point - time of max) / width",
        "skewness of channel 2",
        "skewness of channel 3",
        "half-width of channel 1 / width of channel 2",
        "half-width of channel 2 / width of channel 2",
        "half-width of channel 3 / width of channel 2",
        "width of channel 1 / width of channel 2",
        "width of channel 3 / width of channel 2",
        "(time of max ch2 - time of max ch1) / width of channel 2",
        "(time of max ch3 - time of max ch2) / width of channel 2",
    };
    return d;
}

std::string_view to_string(Rejection r) noexcept {
    switch (r) {
        case Rejection::none: return "none";
        case Rejection::too_short: return "too_short";
        case Rejection::not_finite: return "not_finite";
        case Rejection::low_amplitude: return "low_amplitude";
        case Rejection::incomplete_start: return "incomplete_start";
        case Rejection::incomplete_end: return "incomplete_end";
        case Rejection::zero_width: return "zero_width";
    }
    return "?";
}

namespace {

// Maps a (possibly fractional) sample position to the configured time base.
struct Clock {
    std::span<const double> time;  // empty: sample indices
    double at(double pos) const {
        if (time.empty()) return pos;
        const double fl = std::floor(pos);
        const auto i = static_cast<std::size_t>(fl);
        if (i + 1 >= time.size()) return time.back();
        return time[i] + (pos - fl) * (time[i + 1] - time[i]);
    }
};

// Position where the series crosses `level` between samples a (below) and b (at or above).
double crossing(std::span<const double> x, std::size_t below, std::size_t above, double level) {
    const double xb = x[below], xa = x[above];
    if (xa == xb) return static_cast<double>(above);
    const double frac = (level - xb) / (xa - xb);  // in [0, 1] by construction
    return static_cast<double>(below) + frac * (static_cast<double>(above) - static_cast<double>(below));
}

std::string percent(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f%%", v * 100.0);
    return buf;
}
std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

void measure(std::span<const double> s, const FeatureSettings& cfg, const Clock& clock, ChannelPeak& out) {
    const Peak& p = out.peak;
    const std::size_t n = s.size();
    out.amplitude = p.max;
    if (!(p.max > cfg.min_amplitude)) {
        out.rejection = Rejection::low_amplitude;
        return;
    }
    if (cfg.require_complete_peak && !p.closed_start) {
        out.rejection = Rejection::incomplete_start;
        return;
    }
    if (cfg.require_complete_peak && !p.closed_end) {
        out.rejection = Rejection::incomplete_end;
        return;
    }
    const double threshold = cfg.peak_fraction * p.max;
    double start = static_cast<double>(p.first), end = static_cast<double>(p.last);
    if (cfg.interpolate_crossings) {
        if (p.closed_start) start = crossing(s, p.first - 1, p.first, threshold);
        if (p.closed_end) end = crossing(s, p.last + 1, p.last, threshold);
    }
    out.t_start = clock.at(start);
    out.t_end = clock.at(end);
    out.t_max = clock.at(static_cast<double>(p.max_index));
    out.width = out.t_end - out.t_start;
    if (!(out.width > 0.0)) {
        out.rejection = Rejection::zero_width;
        return;
    }
    out.skewness = (0.5 * (out.t_start + out.t_end) - out.t_max) / out.width;

    const double half = 0.5 * p.max;
    std::size_t a = p.max_index, b = p.max_index;
    if (cfg.half_width == HalfWidthRule::outermost) {
        a = p.first;
        while (s[a] < half) ++a;  // terminates at max_index at the latest
        b = p.last;
        while (s[b] < half) --b;
    } else {
        while (a > 0 && s[a - 1] >= half) --a;
        while (b + 1 < n && s[b + 1] >= half) ++b;
    }
    double ha = static_cast<double>(a), hb = static_cast<double>(b);
    if (cfg.interpolate_crossings) {
        if (a > 0 && s[a - 1] < half) ha = crossing(s, a - 1, a, half);
        if (b + 1 < n && s[b + 1] < half) hb = crossing(s, b + 1, b, half);
    }
    out.half_width = clock.at(hb) - clock.at(ha);
}

std::string describe(std::size_t channel, const ChannelPeak& c, std::span<const double> s,
                     const FeatureSettings& cfg) {
    std::string r = "ch" + std::to_string(channel + 1) + " " + std::string(to_string(c.rejection));
    switch (c.rejection) {
        case Rejection::low_amplitude:
            r += " (max " + number(c.amplitude) + " <= " + number(cfg.min_amplitude) + ")";
            break;
        case Rejection::incomplete_start:
            r += " (still " + percent(s.front() / c.peak.max) + " of max at the first sample)";
            break;
        case Rejection::incomplete_end:
            r += " (still " + percent(s.back() / c.peak.max) + " of max at the last sample)";
            break;
        case Rejection::too_short: r += " (" + std::to_string(s.size()) + " samples)"; break;
        case Rejection::zero_width: r += " (one-sample peak)"; break;
        default: break;
    }
    return r;
}

}  // namespace

FeatureExtractor::FeatureExtractor(FeatureSettings settings) : settings_(settings) {}

Result<TrialFeatures> FeatureExtractor::extract(const std::vector<std::vector<double>>& channels,
                                                std::span<const double> time) {
    std::array<std::span<const double>, kChannels> spans;
    if (channels.size() != kChannels)
        return Error{ErrorCode::invalid_argument, "feature extraction needs exactly 3 channels, got " +
                                                      std::to_string(channels.size())};
    for (std::size_t c = 0; c < kChannels; ++c) spans[c] = channels[c];
    return extract(std::span<const std::span<const double>>(spans), time);
}

Result<TrialFeatures> FeatureExtractor::extract(std::span<const std::span<const double>> channels,
                                                std::span<const double> time) {
    const FeatureSettings& cfg = settings_;
    if (channels.size() != kChannels)
        return Error{ErrorCode::invalid_argument, "feature extraction needs exactly 3 channels, got " +
                                                      std::to_string(channels.size())};
    const std::size_t n = channels[0].size();
    for (std::size_t c = 1; c < kChannels; ++c)
        if (channels[c].size() != n)
            return Error{ErrorCode::invalid_argument, "channel " + std::to_string(c + 1) + " has " +
                                                          std::to_string(channels[c].size()) +
                                                          " samples but channel 1 has " + std::to_string(n)};
    Clock clock;
    if (cfg.time_base == TimeBase::timestamps) {
        if (time.size() != n)
            return Error{ErrorCode::invalid_argument, "time_base 'timestamps' needs a time column of " +
                                                          std::to_string(n) + " samples, got " +
                                                          std::to_string(time.size())};
        clock.time = time;
    }

    TrialFeatures tf;
    tf.values.fill(std::numeric_limits<double>::quiet_NaN());
    // One pass per channel for the structural checks and the raw maximum.
    std::array<double, kChannels> raw_max{};
    bool finite_all = true;
    for (std::size_t c = 0; c < kChannels; ++c) {
        auto& ch = tf.channels[c];
        if (n < 3) {
            ch.rejection = Rejection::too_short;
        } else {
            bool finite = true;
            double m = -std::numeric_limits<double>::infinity();
            for (const double v : channels[c]) {
                finite &= std::isfinite(v);
                m = std::max(m, v);
            }
            raw_max[c] = m;
            if (!finite) ch.rejection = Rejection::not_finite;
        }
        if (ch.rejection != Rejection::none) finite_all = false;
    }

    // A fixed window, or one shared by the three channels; 0: each channel its own.
    int fixed_window = cfg.smoothing_window > 0 ? cfg.smoothing_window : 0;
    if (fixed_window == 0 && cfg.window_scope == WindowScope::shared && finite_all)
        fixed_window = smoothing_window_shared(channels, cfg.smoothing_factor);

    for (std::size_t c = 0; c < kChannels; ++c) {
        auto& ch = tf.channels[c];
        auto& sm = smoothed_[c];
        const auto raw = channels[c];
        if (ch.rejection != Rejection::none) {
            sm.assign(raw.begin(), raw.end());
            continue;
        }
        int window = fixed_window;
        if (window == 0) {
            // Each channel's own window (also the fallback of the shared scope
            // when another channel is already rejected). Smoothing is a
            // normalised positive average, so it never raises the maximum: a
            // channel whose raw maximum is already below the validity threshold
            // is rejected without paying for its window.
            if (!(raw_max[c] > cfg.min_amplitude)) {
                sm.assign(raw.begin(), raw.end());
                ch.window = 0;
                ch.peak = find_peak(sm, cfg.peak_fraction);
                ch.amplitude = ch.peak.max;
                ch.rejection = Rejection::low_amplitude;
                continue;
            }
            window = smoothing_window(raw, cfg.smoothing_factor);
        }
        ch.window = window;
        sm.resize(n);
        gaussian_smooth(raw, window, sm);
        ch.peak = find_peak(sm, cfg.peak_fraction);
        measure(sm, cfg, clock, ch);
    }

    tf.clean = true;
    for (std::size_t c = 0; c < kChannels; ++c) {
        const auto& ch = tf.channels[c];
        if (ch.rejection == Rejection::none) continue;
        tf.clean = false;
        if (!tf.reason.empty()) tf.reason += "; ";
        tf.reason += describe(c, ch, smoothed_[c], cfg);
    }
    if (!tf.clean) return tf;

    const auto& c1 = tf.channels[0];
    const auto& c2 = tf.channels[1];
    const auto& c3 = tf.channels[2];
    const double w2 = c2.width;
    auto& f = tf.values;
    f[0] = c1.amplitude;
    f[1] = c2.amplitude;
    f[2] = c3.amplitude;
    f[3] = c1.skewness;
    f[4] = c2.skewness;
    f[5] = c3.skewness;
    f[6] = c1.half_width / w2;
    f[7] = c2.half_width / w2;
    f[8] = c3.half_width / w2;
    f[9] = c1.width / w2;
    f[10] = c3.width / w2;
    f[11] = (c2.t_max - c1.t_max) / w2;
    f[12] = (c3.t_max - c2.t_max) / w2;
    return tf;
}

}  // namespace rollsense::features
