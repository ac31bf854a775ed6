// Seeded shuffling for fold partitions and the optimiser's candidates. Fully
// specified (splitmix64), so a seed gives the same folds on every platform.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "rollsense/random.hpp"

namespace rollsense::learn {

class SplitMix {
public:
    explicit SplitMix(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        const std::uint64_t z = random::splitmix64(state_);
        state_ += random::kGoldenGamma;
        return z;
    }
    std::uint64_t below(std::uint64_t n) {
        __extension__ using u128 = unsigned __int128;
        return static_cast<std::uint64_t>((static_cast<u128>(next()) * n) >> 64);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

    template <class T>
    void shuffle(std::vector<T>& v) {
        for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[below(i)]);
    }

private:
    std::uint64_t state_;
};

}  // namespace rollsense::learn
