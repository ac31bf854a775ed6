// A STAND-IN preparation of recorded trials into fixed-length series, for this
// bench only, until the analysis layer's rule (cropping to the contact,
// resampling, normalising) lands: smooth each channel with a 5-sample moving
// average, subtract its baseline (the median of the first 5 samples), crop to
// the span where the channel sum exceeds 10 % of its peak, resample linearly
// to `length` and z-normalise each channel.
#pragma once

#include <filesystem>

#include "rollsense/classifier.hpp"
#include "rollsense/status.hpp"

namespace bench {

// The dataset's trials (only clean ones when features.csv says which) as a
// series table, classes in order of first appearance.
rollsense::Result<rollsense::FeatureTable> prepare_dataset(const std::filesystem::path& dir, std::size_t length,
                                                           std::size_t& skipped, bool z_normalise = true,
                                                           double crop = 0.1);

// Three separable shapes (bump, two bumps, ramp) on three channels, shifted and noisy.
rollsense::FeatureTable synthetic_shapes(std::size_t per_class, std::size_t length, std::uint64_t seed);

}  // namespace bench
