// Power spectrum bins of the smoothing heuristic by Goertzel's recurrence,
// several bins per pass over the data (internal to the feature pipeline).
//
// Bin k of the zero-padded 2N-point DFT of a real series x (frequency πk/N):
//   s[i] = (x[i] − s[i−2]) + q·s[i−1],   q = 2·cos(πk/N),
//   |F[k]|² = s1² + s2² − q·s1·s2   (s1, s2: the last two states),
// evaluated in exactly this order whatever the pass width, so a bin's value does
// not depend on which kernel computed it or on the bins computed beside it.
#pragma once

#include <cstddef>
#include <span>

namespace rollsense::features::goertzel {

// The widest pass any kernel makes.
inline constexpr std::size_t kMaxBinsPerPass = 16;

// Bins per pass of the kernel this CPU runs: 16 with AVX2, 8 otherwise. The
// recurrences of a pass are independent, so they fill the FP units instead of
// waiting on one chain's latency: a pass costs little more than one bin did.
std::size_t bins_per_pass() noexcept;

// q[k] = 2·cos(πk/n) for k = 0 … count−1, cached per thread for the last few
// lengths n (a dataset has a handful of trial lengths). The pointer is valid
// until the next call on this thread.
const double* coefficients(std::size_t n, std::size_t count);

// |F[k]|² (≥ 0: rounding below zero is clamped) for the bins_per_pass() bins
// whose coefficients are q[0 …]; written to power[0 …].
void power(std::span<const double> x, const double* q, double* power) noexcept;

// The kernels behind power(), exposed so that tests can compare them with each
// other and with the one-bin recurrence. power_avx2 needs simd::has_avx2().
void power_generic(std::span<const double> x, const double* q, double* power) noexcept;  // 8 bins
void power_avx2(std::span<const double> x, const double* q, double* power) noexcept;     // 16 bins

}  // namespace rollsense::features::goertzel
