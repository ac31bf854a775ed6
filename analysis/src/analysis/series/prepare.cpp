// The series preparation rule; each step's why is in docs/series-preparation.md.
#include "analysis/series/prepare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rollsense/features/smoothing.hpp"

namespace rollsense::series {
namespace {

// Below this the contact, its margins and a baseline cannot all be found.
constexpr std::size_t kMinSamples = 8;
// Fewer samples outside the window than this give no trustworthy median.
constexpr std::size_t kMinBaselineSamples = 3;

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

PreparedSeries refused(Refusal r, std::string reason) {
    PreparedSeries p;
    p.refusal = r;
    p.reason = std::string(to_string(r)) + " (" + reason + ")";
    return p;
}

double median_of(std::vector<double>& v) {
    const std::size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
    double m = v[mid];
    if (v.size() % 2 == 0) {
        const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
        m = 0.5 * (lower + m);
    }
    return m;
}

// Lower quartile: the level a channel rests at, as long as its own contact
// covers less than three quarters of the recording. Computed before the
// contact is known, so it must not need it.
double lower_quartile(std::span<const double> x) {
    std::vector<double> v(x.begin(), x.end());
    const std::size_t q = v.size() / 4;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(q), v.end());
    return v[q];
}

// Linear interpolation at fractional index t; outside the recording the edge
// sample is held (the margins may reach past a short recording's ends).
double sample_at(std::span<const double> x, double t) {
    const double last = static_cast<double>(x.size() - 1);
    if (t <= 0.0) return x.front();
    if (t >= last) return x.back();
    const auto i = static_cast<std::size_t>(t);
    const double f = t - static_cast<double>(i);
    return x[i] + f * (x[i + 1] - x[i]);
}

// Where the reading crosses `level` between samples a and b (s[a] < level ≤ s[b]
// or the reverse), as a fractional index: contact bounds move continuously
// when the contact is stretched, instead of in whole samples.
double crossing(std::span<const double> s, std::size_t a, std::size_t b, double level) {
    const double d = s[b] - s[a];
    const double f = d != 0.0 ? (level - s[a]) / d : 0.0;
    return static_cast<double>(a) + std::clamp(f, 0.0, 1.0) * (static_cast<double>(b) - static_cast<double>(a));
}

}  // namespace

std::string_view to_string(Amplitude a) noexcept {
    switch (a) {
        case Amplitude::global_scale: return "global_scale";
        case Amplitude::z_per_channel: return "z_per_channel";
    }
    return "?";
}

std::string_view to_string(TimeAxis t) noexcept {
    switch (t) {
        case TimeAxis::contact: return "contact";
        case TimeAxis::roll_relative: return "roll_relative";
    }
    return "?";
}

std::string_view to_string(Refusal r) noexcept {
    switch (r) {
        case Refusal::none: return "none";
        case Refusal::too_short: return "too_short";
        case Refusal::too_many_invalid: return "too_many_invalid";
        case Refusal::invalid_gap: return "invalid_gap";
        case Refusal::no_contact: return "no_contact";
        case Refusal::incomplete_contact: return "incomplete_contact";
    }
    return "?";
}

Status validate(const SeriesSettings& s) {
    auto bad = [](const std::string& what) {
        return Status{ErrorCode::invalid_argument, "series settings: " + what};
    };
    if (s.length < 2) return bad("length " + std::to_string(s.length) + " must be at least 2");
    if (s.detect_window < 1) return bad("detect_window " + std::to_string(s.detect_window) + " must be at least 1");
    if (!(s.contact_fraction > 0.0 && s.contact_fraction < 1.0))
        return bad("contact_fraction " + fmt(s.contact_fraction) + " must lie in (0, 1)");
    if (!(s.noise_floor >= 0.0)) return bad("noise_floor " + fmt(s.noise_floor) + " must be ≥ 0");
    if (!(s.min_amplitude > 0.0)) return bad("min_amplitude " + fmt(s.min_amplitude) + " must be > 0");
    if (!(s.margin >= 0.0 && s.margin <= 1.0)) return bad("margin " + fmt(s.margin) + " must lie in [0, 1]");
    if (!(std::isfinite(s.scale) && s.scale > 0.0)) return bad("scale " + fmt(s.scale) + " must be finite and > 0");
    if (!(s.z_floor > 0.0)) return bad("z_floor " + fmt(s.z_floor) + " must be > 0");
    if (!(s.max_invalid_fraction >= 0.0 && s.max_invalid_fraction < 1.0))
        return bad("max_invalid_fraction " + fmt(s.max_invalid_fraction) + " must lie in [0, 1)");
    return {};
}

Result<PreparedSeries> prepare_series(const TrialData& trial, std::span<const std::size_t> channels,
                                      const SeriesSettings& settings) {
    if (auto st = validate(settings); !st) return st.error();
    if (channels.empty())
        return Error{ErrorCode::invalid_argument, "prepare_series: no channel chosen; pass at least one index"};
    const std::size_t total = trial.samples();
    for (std::size_t c : channels) {
        if (c >= trial.channels.size())
            return Error{ErrorCode::invalid_argument, "prepare_series: channel index " + std::to_string(c) +
                                                          " out of range (the trial has " +
                                                          std::to_string(trial.channels.size()) + " channels)"};
        if (trial.channels[c].size() != total)
            return Error{ErrorCode::invalid_argument,
                         "prepare_series: channel index " + std::to_string(c) + " has " +
                             std::to_string(trial.channels[c].size()) + " samples but the time column has " +
                             std::to_string(total)};
    }
    if (!trial.valid.empty() && trial.valid.size() != total)
        return Error{ErrorCode::invalid_argument, "prepare_series: the valid column has " +
                                                      std::to_string(trial.valid.size()) +
                                                      " entries but the time column has " + std::to_string(total)};

    // The prefix only truncates: everything after it is the same rule.
    const bool truncated = settings.prefix > 0 && settings.prefix < total;
    const bool cut = truncated || settings.open_end;
    const std::size_t n = truncated ? settings.prefix : total;
    if (n < kMinSamples)
        return refused(Refusal::too_short, std::to_string(n) + " samples" + (cut ? " in the prefix" : "") + " < " +
                                               std::to_string(kMinSamples));

    // 1. Invalid samples: a failed read (valid = 0) or a non-finite reading on a
    // chosen channel. Isolated ones are bridged; many, or a long run, refuse.
    std::vector<std::uint8_t> bad(n, 0);
    std::size_t invalid = 0, run = 0, longest = 0;
    for (std::size_t i = 0; i < n; ++i) {
        bool b = !trial.valid.empty() && trial.valid[i] == 0;
        for (std::size_t c : channels) b = b || !std::isfinite(trial.channels[c][i]);
        bad[i] = b;
        invalid += b;
        run = b ? run + 1 : 0;
        longest = std::max(longest, run);
    }
    if (invalid == n || static_cast<double>(invalid) > settings.max_invalid_fraction * static_cast<double>(n))
        return refused(Refusal::too_many_invalid, std::to_string(invalid) + " of " + std::to_string(n) +
                                                      " samples invalid; at most " +
                                                      fmt(100.0 * settings.max_invalid_fraction) + "% allowed");
    if (longest > settings.max_gap)
        return refused(Refusal::invalid_gap, std::to_string(longest) + " invalid samples in a row; at most " +
                                                 std::to_string(settings.max_gap) + " are bridged");

    const std::size_t nc = channels.size();
    std::vector<std::vector<double>> x(nc);
    for (std::size_t k = 0; k < nc; ++k) {
        const auto& src = trial.channels[channels[k]];
        auto& dst = x[k];
        dst.assign(src.begin(), src.begin() + static_cast<std::ptrdiff_t>(n));
        std::size_t prev = n;  // last valid index seen, n = none yet
        for (std::size_t i = 0; i < n; ++i) {
            if (bad[i]) continue;
            if (prev + 1 < i || (prev == n && i > 0)) {  // bridge (prev, i), or hold the first valid backwards
                for (std::size_t j = prev == n ? 0 : prev + 1; j < i; ++j)
                    dst[j] = prev == n ? dst[i]
                                       : dst[prev] + (dst[i] - dst[prev]) * static_cast<double>(j - prev) /
                                                         static_cast<double>(i - prev);
            }
            prev = i;
        }
        for (std::size_t j = prev + 1; j < n; ++j) dst[j] = dst[prev];  // hold the last valid forwards
    }

    // 2. The contact, on lightly smoothed channels: per touched channel the
    // samples around its maximum still above its threshold (the paper's walk
    // from the maximum, at contact_fraction instead of 5 %); the contact is
    // the span of all of them. Walking from the maximum ignores noise spikes
    // elsewhere in the recording.
    double start = static_cast<double>(n - 1), end = 0.0;
    bool touched_any = false, open_start = false, open_end = false;
    double largest_rise = -1.0;
    std::size_t largest_channel = channels[0];
    std::vector<double> rest(nc);
    for (std::size_t k = 0; k < nc; ++k) {
        const std::vector<double> s = features::gaussian_smooth(x[k], settings.detect_window);
        rest[k] = lower_quartile(s);
        const auto top = static_cast<std::size_t>(std::max_element(s.begin(), s.end()) - s.begin());
        const double rise = s[top] - rest[k];
        if (rise > largest_rise) largest_rise = rise, largest_channel = channels[k];
        if (rise < settings.min_amplitude) continue;
        touched_any = true;
        const double level = rest[k] + std::max(settings.contact_fraction * rise, settings.noise_floor);
        std::size_t a = top, b = top;
        while (a > 0 && s[a - 1] >= level) --a;
        while (b + 1 < n && s[b + 1] >= level) ++b;
        if (a == 0) open_start = true;
        if (b + 1 == n) open_end = true;
        start = std::min(start, a == 0 ? 0.0 : crossing(s, a - 1, a, level));
        end = std::max(end, b + 1 == n ? static_cast<double>(n - 1) : crossing(s, b, b + 1, level));
    }
    if (!touched_any)
        return refused(Refusal::no_contact, "largest rise " + fmt(largest_rise) + " on channel index " +
                                                std::to_string(largest_channel) + " < min_amplitude " +
                                                fmt(settings.min_amplitude) + (cut ? " within the prefix" : ""));
    if (settings.require_complete_contact && open_start)
        return refused(Refusal::incomplete_contact, "a channel is already in contact at the first sample");
    if (settings.require_complete_contact && open_end && !cut)
        return refused(Refusal::incomplete_contact, "a channel is still in contact at the last sample");

    PreparedSeries out;
    out.ok = true;
    out.invalid_samples = invalid;
    out.contact_start = start;
    out.contact_end = end;
    // Margins scale with the contact, so they are the same share of the series
    // at every speed; an open side (cut off by the recording or the prefix)
    // gets none — there is nothing beyond it to show.
    const double m = settings.margin * (end - start);
    out.window_start = open_start ? start : start - m;
    out.window_end = open_end ? end : end + m;

    // 3. Baseline: the median of each channel outside the window (the object
    // not pressing); robust to the noise and to a single spike. With too few
    // such samples, the channel's resting level found above.
    out.baseline.resize(nc);
    for (std::size_t k = 0; k < nc; ++k) {
        std::vector<double> outside;
        for (std::size_t i = 0; i < n; ++i) {
            const double t = static_cast<double>(i);
            if (t < out.window_start || t > out.window_end) outside.push_back(x[k][i]);
        }
        out.baseline[k] = outside.size() >= kMinBaselineSamples ? median_of(outside) : rest[k];
    }

    // 4. Time: resample the window (or, outside the paper's rule, the whole
    // recording) to `length` samples.
    const double ws = settings.time_axis == TimeAxis::contact ? out.window_start : 0.0;
    const double we = settings.time_axis == TimeAxis::contact ? out.window_end : static_cast<double>(n - 1);
    const std::size_t L = settings.length;
    out.values.resize(nc * L);
    for (std::size_t k = 0; k < nc; ++k) {
        double* row = out.values.data() + k * L;
        for (std::size_t j = 0; j < L; ++j) {
            const double t = ws + (we - ws) * static_cast<double>(j) / static_cast<double>(L - 1);
            row[j] = sample_at(x[k], t) - out.baseline[k];
        }
        // 5. Amplitude.
        if (settings.amplitude == Amplitude::global_scale) {
            for (std::size_t j = 0; j < L; ++j) row[j] *= settings.scale;
        } else {
            double mean = 0.0;
            for (std::size_t j = 0; j < L; ++j) mean += row[j];
            mean /= static_cast<double>(L);
            double var = 0.0;
            for (std::size_t j = 0; j < L; ++j) var += (row[j] - mean) * (row[j] - mean);
            const double sd = std::max(std::sqrt(var / static_cast<double>(L)), settings.z_floor);
            for (std::size_t j = 0; j < L; ++j) row[j] = (row[j] - mean) / sd;
        }
    }
    return out;
}

}  // namespace rollsense::series
