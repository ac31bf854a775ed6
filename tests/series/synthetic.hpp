// Synthetic trials for the series tests: three Gaussian bumps (the three
// barometers pressed one after another) inside a contact, flat elsewhere,
// optionally with the contact stretched in time and with reading noise.
#pragma once

#include <cmath>
#include <cstddef>
#include <random>

#include "rollsense/dataset.hpp"

namespace rollsense::testing {

struct SyntheticTrial {
    std::size_t samples = 200;
    double contact_start = 50.0;   // sample index where the contact begins
    double contact_length = 80.0;  // samples, before stretching
    double stretch = 1.0;          // the contact only takes this many times longer (slower crossing)
    double noise = 0.0;            // uniform ± noise on every reading
    unsigned seed = 1;
};

// The bumps in "contact time" u (sample indices of the unstretched trial).
inline double bumps(std::size_t channel, double u, double a, double len) {
    static constexpr double centre[3] = {0.30, 0.50, 0.70}, sigma[3] = {0.08, 0.10, 0.07},
                            height[3] = {0.45, 0.50, 0.30};
    const double z = (u - (a + centre[channel] * len)) / (sigma[channel] * len);
    return height[channel] * std::exp(-0.5 * z * z);
}

inline TrialData make_trial(const SyntheticTrial& s) {
    const double a = s.contact_start, len = s.contact_length;
    const double extra = (s.stretch - 1.0) * len;  // samples the stretch adds
    const auto n = static_cast<std::size_t>(std::lround(static_cast<double>(s.samples) + extra));
    TrialData t;
    t.channels.assign(3, std::vector<double>(n));
    t.valid.assign(n, 1);
    std::mt19937 rng(s.seed);
    std::uniform_real_distribution<double> noise(-s.noise, s.noise);
    for (std::size_t i = 0; i < n; ++i) {
        const double x = static_cast<double>(i);
        // Before the contact time runs as recorded; inside it runs `stretch`
        // times slower; after it the rest of the recording, unchanged.
        const double u = x < a ? x : x <= a + s.stretch * len ? a + (x - a) / s.stretch : x - extra;
        t.time.push_back(x / 31.1);
        for (std::size_t c = 0; c < 3; ++c) t.channels[c][i] = bumps(c, u, a, len) + (s.noise > 0 ? noise(rng) : 0.0);
    }
    return t;
}

}  // namespace rollsense::testing
