// A small recorded dataset for the report tests: the paper's nine objects at
// two speeds, peaks whose spacing, width and shape depend on the object, and
// one polygon trial per object whose ch3 never leaves the sensor (rejected).
#pragma once

#include <filesystem>

namespace rollsense::test {

inline constexpr int kSyntheticRepetitions = 6;
inline constexpr int kSyntheticSpeeds = 2;
inline constexpr int kSyntheticObjects = 9;

// Writes the dataset (with a run-info.csv) into `dir`, which must not exist.
void write_synthetic_dataset(const std::filesystem::path& dir);

}  // namespace rollsense::test
