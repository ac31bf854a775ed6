// Synthetic raw trials for the benchmark, standing in for a recorded dataset
// when none is given: 9 objects × 3 speeds × 50 runs with the paper's sample
// counts, bump-shaped pressure peaks whose shape depends on the object (size
// sets the contact width and the channel delays, flat faces add lobes whose
// phase depends on a random orientation), a random start position, white
// noise of σ ≈ 0.004, and polygon trials that sometimes stop on the sensor
// (incomplete peak → rejected, as the paper's 186).
//
// This is not the physics of simulation.md (the sim plugin does that); it is a
// realistic workload for timing and a classification problem of similar
// difficulty, so the accuracy comparison with scikit-learn is meaningful.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct SyntheticTrial {
    std::string id, object, speed;
    int repetition = 0;
    std::vector<double> time;
    std::vector<std::vector<double>> channels;  // 3 × N
};

std::vector<SyntheticTrial> synthetic_trials(int runs_per_condition, std::uint64_t seed);

}  // namespace bench
