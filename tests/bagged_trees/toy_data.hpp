// Small synthetic feature tables with known structure for the classifier tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "rollsense/classifier.hpp"

namespace toy {

// Deterministic uniform [0, 1) (LCG), so tests never depend on <random>'s distributions.
struct Lcg {
    std::uint64_t s;
    double next() {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(s >> 11) / 9007199254740992.0;
    }
    double normal() {  // Box–Muller
        const double u1 = std::max(next(), 1e-300), u2 = next();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    }
};

inline rollsense::FeatureTable empty_table(std::size_t features, std::size_t classes) {
    rollsense::FeatureTable t;
    for (std::size_t f = 0; f < features; ++f) t.feature_names.push_back("F" + std::to_string(f + 1));
    for (std::size_t c = 0; c < classes; ++c) t.class_names.push_back("K" + std::to_string(c));
    return t;
}

// Three classes decided by x0 alone (x0 < 1/3, < 2/3, else); x1, x2 are noise.
inline rollsense::FeatureTable separable(std::size_t rows, std::uint64_t seed) {
    auto t = empty_table(3, 3);
    Lcg g{seed};
    for (std::size_t r = 0; r < rows; ++r) {
        const double x0 = g.next();
        t.x.push_back(x0);
        t.x.push_back(g.next());
        t.x.push_back(g.next());
        t.y.push_back(x0 < 1.0 / 3 ? 0 : x0 < 2.0 / 3 ? 1 : 2);
        ++t.rows;
    }
    return t;
}

// Two Gaussian classes in 2-D whose means are 2 apart (unit variance): the
// Bayes-optimal accuracy is Φ(1) = 84.1 %, so nothing can reach 100 %.
inline rollsense::FeatureTable overlapping(std::size_t rows, std::uint64_t seed) {
    auto t = empty_table(2, 2);
    Lcg g{seed};
    for (std::size_t r = 0; r < rows; ++r) {
        const int y = static_cast<int>(r % 2);
        t.x.push_back(g.normal() + (y ? 1.0 : -1.0));
        t.x.push_back(g.normal());
        t.y.push_back(y);
        ++t.rows;
    }
    return t;
}

// Four classes from four features with many tied values, the way measured
// features are: x0 continuous, x1 on a 0.25 grid, x2 a whole number 0–3, x3
// constant except in one row in ten; the class is x2 blurred by x0 and noise.
inline rollsense::FeatureTable ties(std::size_t rows, std::uint64_t seed) {
    auto t = empty_table(4, 4);
    Lcg g{seed};
    for (std::size_t r = 0; r < rows; ++r) {
        const double x0 = g.next();
        const double x1 = std::round(4.0 * g.next()) / 4.0;
        const double x2 = std::floor(4.0 * g.next());
        const double x3 = r % 10 == 0 ? 1.0 : 0.0;
        t.x.insert(t.x.end(), {x0, x1, x2, x3});
        const double score = x2 + 1.5 * (x0 - 0.5) + 0.6 * g.normal();
        t.y.push_back(static_cast<int>(std::clamp(std::round(score), 0.0, 3.0)));
        ++t.rows;
    }
    return t;
}

}  // namespace toy
