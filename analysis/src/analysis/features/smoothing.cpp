// MATLAB smoothdata's Gaussian window heuristic (classifier.md §1); the filter
// itself is in gaussian_filter.cpp.
//
// The heuristic needs the cumulative power spectrum of the mean-free column,
// zero-padded to 2N, over k = 0 … N−1, and only up to the first bin where the
// normalised cumulative power exceeds τ = 1 − f. For the peaks we smooth
// (light smoothing, τ = 0.95) that bin is small (≈ 10 for a 150-sample bump),
// so instead of a full FFT we evaluate the spectrum bin by bin with Goertzel's
// recurrence (goertzel.hpp: 8 or 16 bins per pass over the data) and get the
// normaliser, the total power of the half spectrum, in O(N) from Parseval's
// theorem.
#include "rollsense/features/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "goertzel.hpp"

namespace rollsense::features {
namespace {

// τ outside (0, 1) decides the window without looking at the data.
bool trivial_window(double tau, std::size_t n, int& window) {
    if (n < 2) {
        window = 1;
        return true;
    }
    if (tau <= 0.0) {
        window = static_cast<int>(n);
        return true;
    }
    if (tau >= 1.0) {
        window = 1;
        return true;
    }
    return false;
}

int window_from_rho(std::size_t rho, std::size_t n) {
    const double denom = static_cast<double>(std::max<std::size_t>(rho > 0 ? rho - 1 : 0, 1));
    const double a = 0.44294 * 2.0 * static_cast<double>(n) / denom;
    const double w = std::ceil(std::sqrt(a * a + 1.0));
    return static_cast<int>(std::min(w, 2.0 * static_cast<double>(n)));
}

// One mean-free column and what its spectrum needs.
struct Column {
    std::vector<double> centred;
    double total = 0.0;  // Σ_{k=0}^{N-1} |F[k]|² of the 2N-point DFT
    double bin0 = 0.0;   // |F[0]|² = (Σc)², zero up to rounding
    double cumulative = 0.0;
    bool constant = true;

    // A constant column (or one that only NaN or ±∞ make look varied) has no
    // spectrum: prepare() marks it constant or leaves total NaN, and either
    // way it takes no part in the window.
    bool active() const { return !constant && total > 0.0; }

    // The column's mean-free copy and its sums, in sample order: the order is
    // part of the result, bit for bit. One pass for the sum and the constancy
    // check, one for the rest, even and odd samples in pairs so that F[N]'s
    // alternating sign needs no test per sample.
    void prepare(std::span<const double> x) {
        const std::size_t n = x.size();
        if (n == 0) {
            constant = true;
            return;
        }
        double sum = 0.0;
        bool varies = false;
        for (const double v : x) {
            sum += v;
            varies |= (v != x[0]);
        }
        constant = !varies;
        if (constant) return;
        const double mean = sum / static_cast<double>(n);
        centred.resize(n);
        double energy = 0.0, f0 = 0.0, fn = 0.0;  // fn: F[N] of the 2N-point DFT, Σ c·(−1)^i
        std::size_t i = 0;
        for (; i + 2 <= n; i += 2) {
            const double e = x[i] - mean, o = x[i + 1] - mean;
            centred[i] = e;
            centred[i + 1] = o;
            energy += e * e;
            f0 += e;
            fn += e;
            energy += o * o;
            f0 += o;
            fn += -o;
        }
        if (i < n) {  // n odd: the last sample is an even one
            const double e = x[i] - mean;
            centred[i] = e;
            energy += e * e;
            f0 += e;
            fn += e;
        }
        // Parseval over all 2N bins gives 2N·Σc²; bins k and 2N−k are equal for
        // real data, so the half k = 0 … N−1 holds (2N·Σc² + |F0|² − |FN|²) / 2.
        total = (2.0 * static_cast<double>(n) * energy + f0 * f0 - fn * fn) / 2.0;
        bin0 = f0 * f0;
        cumulative = 0.0;
    }
};

int window_for_columns(std::span<Column> cols, std::size_t n, double tau) {
    std::size_t active = 0;
    for (const auto& c : cols)
        if (c.active()) ++active;
    if (active == 0) return 1;  // constant data: MATLAB returns the data unsmoothed
    // Bin 0 of a mean-free series is |Σc|², known from prepare(): the sweep
    // starts at bin 1, which saves a whole block when ρ is 5…8.
    double mean_cdf0 = 0.0;
    for (auto& c : cols) {
        if (!c.active()) continue;
        c.cumulative = c.bin0;
        mean_cdf0 += c.cumulative / c.total;
    }
    if (mean_cdf0 / static_cast<double>(active) > tau) return window_from_rho(1, n);
    // Bins k0 … k0+width−1 of every column per step; the cumulative curves are
    // then scanned bin by bin, so the first bin over τ is found exactly as a
    // one-bin-at-a-time sweep finds it (bins past it are computed, not used).
    const std::size_t width = goertzel::bins_per_pass();
    double block[goertzel::kMaxBinsPerPass];
    for (std::size_t k0 = 1; k0 < n; k0 += width) {
        const double* q = goertzel::coefficients(n, k0 + width) + k0;
        double mean_cdf[goertzel::kMaxBinsPerPass] = {};
        for (auto& c : cols) {
            if (!c.active()) continue;
            goertzel::power(c.centred, q, block);
            for (std::size_t j = 0; j < width; ++j) {
                c.cumulative += block[j];
                mean_cdf[j] += c.cumulative / c.total;
            }
        }
        for (std::size_t j = 0; j < width && k0 + j < n; ++j)
            if (mean_cdf[j] / static_cast<double>(active) > tau) return window_from_rho(k0 + j + 1, n);
    }
    // Rounding kept the curve at or just under τ to the end: the last bin.
    return window_from_rho(n, n);
}

thread_local std::vector<Column> tl_columns;

}  // namespace

int smoothing_window(std::span<const double> x, double factor) {
    int window = 1;
    const double tau = 1.0 - factor;
    if (trivial_window(tau, x.size(), window)) return window;
    auto& cols = tl_columns;
    cols.resize(1);
    cols[0].prepare(x);
    return window_for_columns(cols, x.size(), tau);
}

int smoothing_window_shared(std::span<const std::span<const double>> columns, double factor) {
    if (columns.empty()) return 1;
    const std::size_t n = columns.front().size();
    int window = 1;
    if (trivial_window(1.0 - factor, n, window)) return window;
    auto& cols = tl_columns;
    cols.resize(columns.size());
    for (std::size_t i = 0; i < columns.size(); ++i) cols[i].prepare(columns[i]);
    return window_for_columns(cols, n, 1.0 - factor);
}

}  // namespace rollsense::features
