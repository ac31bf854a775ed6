#include "analysis/series/contact_clock.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace rollsense::series {
namespace {

bool valid_at(const TrialData& trial, std::span<const std::size_t> channels, std::size_t i) {
    if (!trial.valid.empty() && trial.valid[i] == 0) return false;
    for (std::size_t c : channels)
        if (!std::isfinite(trial.channels[c][i])) return false;
    return true;
}

// Where the reading crosses `level` between valid samples a < b (linear).
double crossing(double ya, double yb, std::size_t a, std::size_t b, double level) {
    const double f = yb != ya ? std::clamp((level - ya) / (yb - ya), 0.0, 1.0) : 0.0;
    return static_cast<double>(a) + f * static_cast<double>(b - a);
}

}  // namespace

std::optional<ContactClock> contact_clock(const TrialData& trial, std::span<const std::size_t> channels,
                                          const SeriesSettings& settings) {
    const std::size_t n = settings.prefix > 0 ? std::min(settings.prefix, trial.samples()) : trial.samples();
    if (!trial.valid.empty() && trial.valid.size() < n) return std::nullopt;
    for (std::size_t c : channels)
        if (c >= trial.channels.size() || trial.channels[c].size() < n) return std::nullopt;
    const std::size_t nc = channels.size();
    std::vector<std::array<double, kClockRestSamples>> first(nc);
    std::vector<double> rest(nc), top(nc, -HUGE_VAL);
    std::vector<std::size_t> valid;  // indices of the valid samples so far: the half-way rise is found among them
    for (std::size_t i = 0; i < n; ++i) {
        if (!valid_at(trial, channels, i)) continue;
        const std::size_t seen = valid.size();
        valid.push_back(i);
        if (seen < kClockRestSamples) {
            for (std::size_t k = 0; k < nc; ++k) first[k][seen] = trial.channels[channels[k]][i];
            if (seen + 1 == kClockRestSamples)
                for (std::size_t k = 0; k < nc; ++k) {
                    auto& r = first[k];
                    std::nth_element(r.begin(), r.begin() + kClockRestSamples / 2, r.end());
                    rest[k] = r[kClockRestSamples / 2];
                }
            continue;
        }
        for (std::size_t k = 0; k < nc; ++k) {
            const auto& x = trial.channels[channels[k]];
            top[k] = std::max(top[k], x[i]);
            const double half = rest[k] + 0.5 * (top[k] - rest[k]);
            if (top[k] - rest[k] < settings.min_amplitude || x[i] >= half - kClockHalfTolerance) continue;
            // Fell through half its maximum: the bump is complete. Its rise
            // through the same level is the last upward crossing before the top.
            const std::size_t prev = valid[valid.size() - 2];
            const double down = crossing(x[prev], x[i], prev, i, half);
            std::size_t j = valid.size() - 2;
            while (j > 0 && x[valid[j]] >= half - kClockHalfTolerance) --j;  // x[valid[j]] < half ≤ x[valid[j + 1]]
            const double up = crossing(x[valid[j]], x[valid[j + 1]], valid[j], valid[j + 1], half);
            if (down > up) return ContactClock{k, up, down - up, i};
        }
    }
    return std::nullopt;
}

double clock_progress(const ContactClock& clock, double units, std::size_t samples) {
    if (samples == 0 || !(units > 0.0)) return 0.0;
    return (static_cast<double>(samples - 1) - clock.zero) / (units * clock.unit);
}

}  // namespace rollsense::series
