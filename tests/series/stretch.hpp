// A recorded trial with part of it slowed down in time: the object crossing
// the array slower, the rest of the recording unchanged (the series rule's
// metamorphic tests, at the preparation and at the prediction level).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "rollsense/dataset.hpp"

namespace rollsense::testing {

// The trial with its samples in [a, b] stretched `factor` times in time
// (linear interpolation of the recorded readings), the rest unchanged.
inline TrialData stretch_contact(const TrialData& t, double a, double b, double factor) {
    const std::size_t n = t.samples();
    const double extra = (factor - 1.0) * (b - a);
    const auto m = static_cast<std::size_t>(std::lround(static_cast<double>(n) + extra));
    TrialData s;
    s.channels.assign(t.channels.size(), std::vector<double>(m));
    s.valid.assign(m, 1);
    for (std::size_t i = 0; i < m; ++i) {
        const double x = static_cast<double>(i);
        double u = x < a ? x : x <= a + factor * (b - a) ? a + (x - a) / factor : x - extra;
        u = std::clamp(u, 0.0, static_cast<double>(n - 1));
        const auto k = std::min(static_cast<std::size_t>(u), n - 2);
        const double f = u - static_cast<double>(k);
        s.time.push_back(x / 31.1);
        for (std::size_t c = 0; c < t.channels.size(); ++c)
            s.channels[c][i] = t.channels[c][k] + f * (t.channels[c][k + 1] - t.channels[c][k]);
    }
    return s;
}

}  // namespace rollsense::testing
