// A separable synthetic multichannel data set for MiniRocket: three shapes
// (one bump, two bumps, a ramp) at random positions, amplitudes and noise, on
// three channels of which the third is noise only.
#pragma once

#include <cmath>
#include <string>

#include "rollsense/classifier.hpp"
#include "rollsense/random.hpp"

namespace shapes {

inline double bump(double t, double centre, double width) {
    const double z = (t - centre) / width;
    return std::exp(-0.5 * z * z);
}

inline rollsense::FeatureTable make(std::size_t per_class, std::size_t length, std::uint64_t seed) {
    rollsense::FeatureTable t;
    t.channel_names = {"p0", "p1", "noise"};
    t.series_length = length;
    t.class_names = {"bump", "two_bumps", "ramp"};
    auto rng = rollsense::random::Xoshiro256ss::named_stream(seed, "shapes");
    const double L = static_cast<double>(length);
    for (std::size_t i = 0; i < per_class * 3; ++i) {
        const int label = static_cast<int>(i % 3);
        const double shift = rng.uniform(-0.15, 0.15) * L, amp = rng.uniform(0.7, 1.3);
        for (std::size_t ch = 0; ch < 3; ++ch) {
            for (std::size_t s = 0; s < length; ++s) {
                const double x = static_cast<double>(s);
                double v = 0.0;
                if (ch < 2) {
                    const double gain = ch == 0 ? amp : 0.6 * amp;
                    if (label == 0) v = bump(x, 0.5 * L + shift, 0.1 * L);
                    if (label == 1) v = bump(x, 0.35 * L + shift, 0.07 * L) + bump(x, 0.65 * L + shift, 0.07 * L);
                    if (label == 2) v = std::clamp((x - 0.2 * L - shift) / (0.6 * L), 0.0, 1.0);
                    v *= gain;
                }
                t.x.push_back(v + 0.1 * rng.normal());
            }
        }
        t.y.push_back(label);
        ++t.rows;
    }
    return t;
}

// Rows [begin, end) of a table as a new table.
inline rollsense::FeatureTable slice(const rollsense::FeatureTable& t, std::size_t begin, std::size_t end) {
    rollsense::FeatureTable s = t;
    s.rows = end - begin;
    s.x.assign(t.x.begin() + static_cast<std::ptrdiff_t>(begin * t.cols()),
               t.x.begin() + static_cast<std::ptrdiff_t>(end * t.cols()));
    s.y.assign(t.y.begin() + static_cast<std::ptrdiff_t>(begin), t.y.begin() + static_cast<std::ptrdiff_t>(end));
    return s;
}

}  // namespace shapes
