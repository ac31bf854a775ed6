// MATLAB smoothdata's Gaussian window heuristic and filter (classifier.md §1).
//
// The heuristic needs the cumulative power spectrum of the mean-free column,
// zero-padded to 2N, over k = 0 … N−1, and only up to the first bin where the
// normalised cumulative power exceeds τ = 1 − f. For the peaks we smooth
// (light smoothing, τ = 0.95) that bin is small (≈ 10 for a 150-sample bump),
// so instead of a full FFT we evaluate the spectrum bin by bin with Goertzel's
// recurrence (one multiply-add per sample and bin) and get the normaliser, the
// total power of the half spectrum, in O(N) from Parseval's theorem.
#include "rollsense/features/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

    void prepare(std::span<const double> x) {
        const std::size_t n = x.size();
        auto [lo, hi] = std::minmax_element(x.begin(), x.end());
        constant = (*lo == *hi);
        if (constant) return;
        double mean = 0.0;
        for (double v : x) mean += v;
        mean /= static_cast<double>(n);
        centred.resize(n);
        double energy = 0.0, f0 = 0.0, fn = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double c = x[i] - mean;
            centred[i] = c;
            energy += c * c;
            f0 += c;
            fn += (i % 2 == 0) ? c : -c;  // F[N] of the 2N-point DFT: Σ c·(−1)^n
        }
        // Parseval over all 2N bins gives 2N·Σc²; bins k and 2N−k are equal for
        // real data, so the half k = 0 … N−1 holds (2N·Σc² + |F0|² − |FN|²) / 2.
        total = (2.0 * static_cast<double>(n) * energy + f0 * f0 - fn * fn) / 2.0;
        bin0 = f0 * f0;
        cumulative = 0.0;
    }

    // |F[k]|² of the 2N-point DFT (frequency πk/N) for four consecutive bins
    // k … k+3 by Goertzel's recurrence. Four independent recurrences per pass
    // hide the latency of each one's dependency chain (≈ 4× faster than one
    // bin at a time); bins beyond N−1 are computed but never used.
    void power4(std::size_t k, double out[4]) const {
        const double n = static_cast<double>(centred.size());
        const double q0 = 2.0 * std::cos(std::numbers::pi * static_cast<double>(k) / n);
        const double q1 = 2.0 * std::cos(std::numbers::pi * static_cast<double>(k + 1) / n);
        const double q2 = 2.0 * std::cos(std::numbers::pi * static_cast<double>(k + 2) / n);
        const double q3 = 2.0 * std::cos(std::numbers::pi * static_cast<double>(k + 3) / n);
        // Named scalars rather than arrays so that all eight states stay in
        // registers; (c − s2) first keeps one multiply and one add on each
        // recurrence's critical path.
        double a1 = 0, a2 = 0, b1 = 0, b2 = 0, c1 = 0, c2 = 0, d1 = 0, d2 = 0;
        for (double c : centred) {
            const double a = (c - a2) + q0 * a1;
            const double b = (c - b2) + q1 * b1;
            const double cc = (c - c2) + q2 * c1;
            const double d = (c - d2) + q3 * d1;
            a2 = a1, a1 = a;
            b2 = b1, b1 = b;
            c2 = c1, c1 = cc;
            d2 = d1, d1 = d;
        }
        out[0] = std::max(0.0, a1 * a1 + a2 * a2 - q0 * a1 * a2);
        out[1] = std::max(0.0, b1 * b1 + b2 * b2 - q1 * b1 * b2);
        out[2] = std::max(0.0, c1 * c1 + c2 * c2 - q2 * c1 * c2);
        out[3] = std::max(0.0, d1 * d1 + d2 * d2 - q3 * d1 * d2);
    }
};

int window_for_columns(std::vector<Column>& cols, std::size_t n, double tau) {
    std::size_t active = 0;
    for (const auto& c : cols)
        if (!c.constant && c.total > 0.0) ++active;
    if (active == 0) return 1;  // constant data: MATLAB returns the data unsmoothed
    // Bin 0 of a mean-free series is |Σc|², known from prepare(): the sweep
    // starts at bin 1, which saves a whole block when ρ is 5…8.
    double mean_cdf0 = 0.0;
    for (auto& c : cols) {
        if (c.constant || c.total <= 0.0) continue;
        c.cumulative = c.bin0;
        mean_cdf0 += c.cumulative / c.total;
    }
    if (mean_cdf0 / static_cast<double>(active) > tau) return window_from_rho(1, n);
    double block[4];
    for (std::size_t k0 = 1; k0 < n; k0 += 4) {
        double mean_cdf[4] = {0, 0, 0, 0};
        for (auto& c : cols) {
            if (c.constant || c.total <= 0.0) continue;
            c.power4(k0, block);
            for (int j = 0; j < 4; ++j) {
                c.cumulative += block[j];
                mean_cdf[j] += c.cumulative / c.total;
            }
        }
        for (std::size_t j = 0; j < 4 && k0 + j < n; ++j)
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

void gaussian_smooth(std::span<const double> x, int window, std::span<double> out) {
    const std::size_t n = x.size();
    if (window < 2 || n == 0) {
        std::copy(x.begin(), x.end(), out.begin());
        return;
    }
    // Offsets −floor(w/2) … ceil(w/2)−1: an even window reaches one sample
    // further into the past, as MATLAB's does.
    const long before = window / 2;
    const long after = (window + 1) / 2 - 1;
    const double sigma = window / 5.0;
    thread_local std::vector<double> weights;
    weights.resize(static_cast<std::size_t>(before + after + 1));
    double full_sum = 0.0;
    for (long e = -before; e <= after; ++e) {
        const double g = std::exp(-static_cast<double>(e * e) / (2.0 * sigma * sigma));
        weights[static_cast<std::size_t>(e + before)] = g;
        full_sum += g;
    }
    const long len = static_cast<long>(n);
    const double* w = weights.data() + before;  // w[e] for e in [-before, after]
    const double* xp = x.data();
    // Edges: only the offsets inside the series, weights renormalised.
    auto edge = [&](long i) {
        const long lo = std::max(-before, -i);
        const long hi = std::min(after, len - 1 - i);
        double num = 0.0, den = 0.0;
        for (long e = lo; e <= hi; ++e) {
            num += w[e] * xp[i + e];
            den += w[e];
        }
        out[static_cast<std::size_t>(i)] = num / den;
    };
    const long first_full = std::min(before, len);
    const long last_full = std::max(first_full, len - after);  // exclusive
    for (long i = 0; i < first_full; ++i) edge(i);
    // Interior: every offset inside. Four outputs at a time, each with its own
    // running sum, so four independent multiply-add chains are in flight
    // instead of one long dependent sum per sample.
    const double inv = 1.0 / full_sum;
    double* o = out.data();
    long i = first_full;
    for (; i + 4 <= last_full; i += 4) {
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
        const double* xi = xp + i;
        for (long e = -before; e <= after; ++e) {
            const double we = w[e];
            a0 += we * xi[e];
            a1 += we * xi[e + 1];
            a2 += we * xi[e + 2];
            a3 += we * xi[e + 3];
        }
        o[i] = a0 * inv;
        o[i + 1] = a1 * inv;
        o[i + 2] = a2 * inv;
        o[i + 3] = a3 * inv;
    }
    for (; i < last_full; ++i) {
        double a = 0.0;
        for (long e = -before; e <= after; ++e) a += w[e] * xp[i + e];
        o[i] = a * inv;
    }
    for (; i < len; ++i) edge(i);
}

std::vector<double> gaussian_smooth(std::span<const double> x, int window) {
    std::vector<double> out(x.size());
    gaussian_smooth(x, window, out);
    return out;
}

}  // namespace rollsense::features
