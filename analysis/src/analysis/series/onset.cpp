#include "analysis/series/onset.hpp"

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

}  // namespace

std::optional<ContactClock> contact_clock(const TrialData& trial, std::span<const std::size_t> channels,
                                          const SeriesSettings& settings) {
    const std::size_t n = settings.prefix > 0 ? std::min(settings.prefix, trial.samples()) : trial.samples();
    for (std::size_t c : channels)
        if (c >= trial.channels.size() || trial.channels[c].size() < n) return std::nullopt;
    std::vector<std::array<double, kOnsetRestSamples>> first(channels.size());
    std::vector<double> rest(channels.size());
    std::size_t seen = 0;
    std::optional<ContactClock> clock;
    double top = 0.0;  // the rising channel's largest reading so far
    for (std::size_t i = 0; i < n; ++i) {
        if (!valid_at(trial, channels, i)) continue;
        if (seen < kOnsetRestSamples) {
            for (std::size_t k = 0; k < channels.size(); ++k) first[k][seen] = trial.channels[channels[k]][i];
            if (++seen == kOnsetRestSamples)
                for (std::size_t k = 0; k < channels.size(); ++k) {
                    auto& r = first[k];
                    std::nth_element(r.begin(), r.begin() + kOnsetRestSamples / 2, r.end());
                    rest[k] = r[kOnsetRestSamples / 2];
                }
            continue;
        }
        if (!clock) {
            double largest = settings.min_amplitude;
            for (std::size_t k = 0; k < channels.size(); ++k) {
                const double rise = trial.channels[channels[k]][i] - rest[k];
                if (rise >= largest) {
                    largest = rise;
                    clock = ContactClock{i, k, std::nullopt};
                }
            }
            if (clock) top = trial.channels[channels[clock->channel]][i];
            continue;
        }
        const double v = trial.channels[channels[clock->channel]][i];
        top = std::max(top, v);
        const double r = rest[clock->channel];
        if (v <= r + 0.5 * (top - r)) {
            clock->unit = i - clock->onset;
            return clock;
        }
    }
    return clock;
}

}  // namespace rollsense::series
