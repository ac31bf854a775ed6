// MATLAB-equivalent Gaussian smoothing: smoothdata(x, 'gaussian', 'SmoothingFactor', f).
//
// The paper smooths every channel with "a Gaussian filter with a smoothing
// coefficient of 0.05", i.e. MATLAB's smoothdata with a smoothing factor. MATLAB
// does not take a window length then; it derives one from the data's spectrum on
// every call (classifier.md §1). Reproducing that heuristic, not just "a Gaussian
// filter", is what makes our features comparable with the paper's.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

namespace rollsense::features {

// Window length MATLAB's smoothdata picks for one column at smoothing factor
// `factor` in [0, 1]: 0 → window 1 (no smoothing), 1 → window N. Constant data
// (or a single sample) gives 1.
int smoothing_window(std::span<const double> x, double factor);

// One window shared by several equally long columns (MATLAB smoothing a matrix):
// the columns' normalised cumulative power curves are averaged. Constant columns
// carry no spectral information and are left out of the average.
int smoothing_window_shared(std::span<const std::span<const double>> columns, double factor);

// Gaussian-weighted moving average with window `window` (σ = window / 5; offsets
// −floor(w/2) … ceil(w/2)−1; at the edges the weights inside the series are
// renormalised, nothing is padded). window < 2 copies the input. `out` must have
// x.size() elements and must not alias `x`.
void gaussian_smooth(std::span<const double> x, int window, std::span<double> out);
std::vector<double> gaussian_smooth(std::span<const double> x, int window);

// The vector kernels the heuristic and the filter run on this CPU: "avx2" or
// "generic" (SSE2 or NEON lanes; ROLLSENSE_SIMD=generic forces it). Results are
// the same bit for bit; only the speed differs. For benchmarks and diagnostics.
std::string_view vector_kernels() noexcept;

}  // namespace rollsense::features
