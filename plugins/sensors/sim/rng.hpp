// The simulation's random numbers: the SDK generator (rollsense/random.hpp)
// with the sim's seeding, so a run seed gives the same dataset on every machine
// and the same dataset as before the generator moved into the SDK.
#pragma once

#include <cstdint>
#include <string_view>

#include "rollsense/random.hpp"

namespace rollsense::sim {

// Seed derivation helpers under the names the sim and its calibration bench use.
inline std::uint64_t mix64(std::uint64_t x) noexcept { return random::splitmix64(x); }
inline std::uint64_t label_hash(std::string_view label) noexcept { return random::fnv1a64(label); }

// Every random "stream" (noise, start position, ...) of a trial is a named
// stream of the trial seed; see sim_model.cpp.
class Rng : public random::Xoshiro256ss {
public:
    explicit Rng(std::uint64_t seed = 0) noexcept : Xoshiro256ss(splitmix64_chain(seed)) {}
    Rng(std::uint64_t seed, std::string_view stream) noexcept : Xoshiro256ss(named_stream(seed, stream)) {}
};

}  // namespace rollsense::sim
