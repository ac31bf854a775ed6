// A small, fully specified random generator (xoshiro256**, seeded through
// splitmix64). std::uniform_int_distribution differs between standard
// libraries; this does not, so a model trained with a seed is the same model
// on every machine and with every thread count.
#pragma once

#include <cstdint>

namespace rollsense::bagged_trees {

class Rng {
public:
    explicit Rng(std::uint64_t seed);
    // A generator for stream `index` of `seed` (one per tree), independent of
    // which thread builds that tree.
    static Rng stream(std::uint64_t seed, std::uint64_t index);

    std::uint64_t next();
    // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift).
    std::uint64_t below(std::uint64_t n);
    // Uniform double in [0, 1).
    double uniform();

private:
    std::uint64_t s_[4];
};

}  // namespace rollsense::bagged_trees
