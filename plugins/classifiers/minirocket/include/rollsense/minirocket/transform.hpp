// The MiniRocket transform (Dempster, Schmidt & Webb, KDD 2021), written from
// the paper: 84 fixed kernels of length 9 (weights −1, with three positions at
// +2), dilations spread exponentially over the series length, padding
// alternating per (kernel, dilation), biases from low-discrepancy quantiles of
// the convolution output of randomly chosen training series, and "proportion
// of positive values" (PPV) pooling. Multivariate as the paper's multivariate
// variant: each (dilation, kernel) combination sums its convolution over a
// random subset of the channels.
//
// Series are float32: PPV only compares a convolution against a bias, so
// single precision keeps the features (counts of crossings) while halving the
// memory traffic and doubling the vector width.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::minirocket {

inline constexpr int kKernelLength = 9;
inline constexpr int kKernels = 84;  // C(9, 3): positions of the three +2 weights

// Kernel k's three +2 positions, kernels in lexicographic order of positions.
std::array<int, 3> kernel_twos(int kernel);

struct TransformOptions {
    int num_features = 10000;            // rounded down to a multiple of 84
    int max_dilations_per_kernel = 32;
    std::uint64_t seed = 1;               // channel subsets and bias examples
};

// One (dilation, kernel) pair: its channels, padding and slice of features.
struct Combination {
    int dilation_index = 0;
    int kernel = 0;
    bool padded = false;
    std::vector<int> channels;  // sorted, distinct
    int first_feature = 0;
    int features = 0;
};

class Transform {
public:
    // Layout of the features (dilations, counts, combinations, channel subsets)
    // for series of `channels` × `length`; biases are left at 0. Errors when the
    // series are shorter than one kernel or the feature count is below 84.
    Status plan(std::size_t channels, std::size_t length, const TransformOptions& options);
    // plan() then biases from the training series (rows × channels × length,
    // channel-major per row). Deterministic for a given seed.
    Status fit(std::span<const float> series, std::size_t rows, std::size_t channels, std::size_t length,
               const TransformOptions& options);

    // Features of `rows` series into out (rows × features(), row-major).
    void transform(std::span<const float> series, std::size_t rows, std::span<float> out, unsigned threads) const;
    // Features of one series (channels × length) into out (features()).
    void transform_one(std::span<const float> series, std::span<float> out) const;

    bool fitted() const { return !combinations_.empty(); }
    std::size_t features() const { return biases_.size(); }
    std::size_t channels() const { return channels_; }
    std::size_t length() const { return length_; }
    const TransformOptions& options() const { return options_; }
    const std::vector<int>& dilations() const { return dilations_; }
    const std::vector<int>& features_per_dilation() const { return features_per_dilation_; }
    const std::vector<Combination>& combinations() const { return combinations_; }
    const std::vector<float>& biases() const { return biases_; }

    // For loading a saved model: replaces the channel subsets and biases of a
    // plan()ned transform; sizes are checked.
    Status restore(std::vector<std::vector<int>> channel_subsets, std::vector<float> biases);

    // The convolution of one series with one combination, full length with
    // zero padding (what biases are drawn from); exposed for tests.
    void convolve(std::span<const float> series, const Combination& c, std::span<float> out) const;

private:
    struct Scratch;
    void dilation_bases(std::span<const float> series, int dilation, Scratch& s) const;
    void combine(const Scratch& s, const Combination& c, float* out) const;

    TransformOptions options_;
    std::size_t channels_ = 0, length_ = 0;
    std::vector<int> dilations_, features_per_dilation_;
    std::vector<Combination> combinations_;  // dilation-major, then kernel
    std::vector<float> biases_;
};

// The low-discrepancy quantile of feature i: frac((i + 1) · φ), φ the golden ratio.
double feature_quantile(std::size_t i);
// numpy's default (linear) quantile of sorted `values`.
float linear_quantile(std::span<const float> values, double q);

}  // namespace rollsense::minirocket
