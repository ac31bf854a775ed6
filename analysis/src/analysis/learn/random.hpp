// Seeded shuffling for fold partitions and the optimiser's candidates. Fully
// specified (splitmix64), so a seed gives the same folds on every platform.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "rollsense/random.hpp"

namespace rollsense::learn {

// The SDK's splitmix64 generator plus a Fisher–Yates shuffle.
class SplitMix : public random::SplitMix64 {
public:
    using random::SplitMix64::SplitMix64;

    template <class T>
    void shuffle(std::vector<T>& v) {
        for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[below(i)]);
    }
};

}  // namespace rollsense::learn
