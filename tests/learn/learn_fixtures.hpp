// Shared by the learning tests: bagged trees made through a factory, as the
// kernel does with plugins, and paper-like synthetic feature rows.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "rollsense/features.hpp"
#include "analysis/learn/cross_validation.hpp"

namespace rollsense::learn::fixtures {

using features::FeatureRow;

inline ClassifierFactory bagged_trees_factory(int* made = nullptr) {
    return [made](const ParamSet& raw) -> Result<ClassifierPtr> {
        auto params = validate_params(bagged_trees::bagged_trees_schema(), raw.values(), "test");
        if (!params) return params.error();
        auto c = std::make_shared<bagged_trees::BaggedTrees>();
        if (auto s = c->on_configure(*params, {}); !s) return s;
        if (made) ++*made;
        return ClassifierPtr(c);
    };
}

// Paper-like rows: 9 objects, the class shifts a few features; some polygon
// trials rejected. `noise` controls overlap.
inline std::vector<FeatureRow> synthetic_rows(int per_class, double noise, std::uint64_t seed) {
    const std::vector<std::string> objects = {"C1", "C2", "C3", "S1", "S2", "P1", "P2", "H1", "H2"};
    std::vector<FeatureRow> rows;
    std::uint64_t s = seed;
    auto uniform = [&] {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(s >> 11) / 9007199254740992.0;
    };
    for (std::size_t o = 0; o < objects.size(); ++o)
        for (int i = 0; i < per_class; ++i) {
            FeatureRow r;
            r.trial_id = objects[o] + "-" + std::to_string(i);
            r.object = objects[o];
            r.clean = !(o >= 3 && i % 7 == 0);
            for (std::size_t k = 0; k < r.values.size(); ++k)
                r.values[k] = (k < 4 ? static_cast<double>(o) * (k + 1) * 0.1 : 0.0) + noise * (uniform() - 0.5);
            if (!r.clean) r.values.fill(std::nan(""));
            rows.push_back(r);
        }
    return rows;
}


}  // namespace rollsense::learn::fixtures
