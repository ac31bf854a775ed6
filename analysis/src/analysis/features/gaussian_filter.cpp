// MATLAB smoothdata's Gaussian filter with a given window (classifier.md §1).
//
// Every output is Σ g(e)·x[i+e] / Σ g(e), summed over e in ascending order and,
// in the interior, multiplied by the precomputed 1/Σ g. The interior is
// computed several outputs at a time in vector lanes, each lane doing exactly
// that scalar sum, so the result does not depend on the path that computed it.
#include <algorithm>
#include <cmath>
#include <vector>

#include "rollsense/features/smoothing.hpp"
#include "simd.hpp"

namespace rollsense::features {
namespace {

// Gaussian weights g(e), e = −before … after, and their sum.
struct Kernel {
    std::vector<double> weights;
    double full_sum = 0.0;
    long before = 0, after = 0;

    void build(int window) {
        // Offsets −floor(w/2) … ceil(w/2)−1: an even window reaches one sample
        // further into the past, as MATLAB's does.
        before = window / 2;
        after = (window + 1) / 2 - 1;
        const double sigma = window / 5.0;
        weights.resize(static_cast<std::size_t>(before + after + 1));
        full_sum = 0.0;
        for (long e = -before; e <= after; ++e) {
            const double g = std::exp(-static_cast<double>(e * e) / (2.0 * sigma * sigma));
            weights[static_cast<std::size_t>(e + before)] = g;
            full_sum += g;
        }
    }
};

// Kernels by window, built on first use per thread: a dataset uses a few dozen
// windows, and recomputing w exponentials per channel was a visible cost.
constexpr int kCachedWindows = 512;
thread_local std::vector<Kernel> tl_kernels;
thread_local Kernel tl_scratch;

const Kernel& kernel_for(int window) {
    if (window >= kCachedWindows) {
        tl_scratch.build(window);
        return tl_scratch;
    }
    auto& cache = tl_kernels;
    if (cache.empty()) cache.resize(kCachedWindows);
    Kernel& k = cache[static_cast<std::size_t>(window)];
    if (k.weights.empty()) k.build(window);
    return k;
}

// Interior outputs i … in blocks of lanes·Count, each lane its own running sum;
// returns the first output not done (fewer than a block remain).
template <class V, int Count>
[[gnu::always_inline]] inline long interior_blocks(const double* xp, const double* w, long before, long after,
                                                   double inv, double* o, long i, long end) {
    constexpr long L = static_cast<long>(simd::lanes<V>);
    constexpr long block = L * Count;
    for (; i + block <= end; i += block) {
        V acc[Count];
#pragma GCC unroll 8
        for (int v = 0; v < Count; ++v) acc[v] = V{};
        const double* xi = xp + i;
        for (long e = -before; e <= after; ++e) {
            const double we = w[e];
#pragma GCC unroll 8
            for (int v = 0; v < Count; ++v) {
                V xv;
                simd::load(xv, xi + e + L * v);
                acc[v] += we * xv;
            }
        }
#pragma GCC unroll 8
        for (int v = 0; v < Count; ++v) simd::store(o + i + L * v, acc[v] * inv);
    }
    return i;
}

long interior_generic(const double* xp, const double* w, long before, long after, double inv, double* o, long i,
                      long end) {
    return interior_blocks<simd::Vec2, 4>(xp, w, before, after, inv, o, i, end);
}

#if ROLLSENSE_HAVE_AVX2_VARIANT
ROLLSENSE_TARGET_AVX2 long interior_avx2(const double* xp, const double* w, long before, long after, double inv,
                                         double* o, long i, long end) {
    return interior_blocks<simd::Vec4, 4>(xp, w, before, after, inv, o, i, end);
}
#endif

}  // namespace

void gaussian_smooth(std::span<const double> x, int window, std::span<double> out) {
    const std::size_t n = x.size();
    if (window < 2 || n == 0) {
        std::copy(x.begin(), x.end(), out.begin());
        return;
    }
    const Kernel& k = kernel_for(window);
    const long before = k.before, after = k.after;
    const long len = static_cast<long>(n);
    const double* w = k.weights.data() + before;  // w[e] for e in [-before, after]
    const double* xp = x.data();
    double* o = out.data();
    // Edges: only the offsets inside the series, weights renormalised.
    auto edge = [&](long i) {
        const long lo = std::max(-before, -i);
        const long hi = std::min(after, len - 1 - i);
        double num = 0.0, den = 0.0;
        for (long e = lo; e <= hi; ++e) {
            num += w[e] * xp[i + e];
            den += w[e];
        }
        o[i] = num / den;
    };
    const long first_full = std::min(before, len);
    const long last_full = std::max(first_full, len - after);  // exclusive
    for (long i = 0; i < first_full; ++i) edge(i);
    // Interior: every offset inside.
    const double inv = 1.0 / k.full_sum;
    long i = first_full;
#if ROLLSENSE_HAVE_AVX2_VARIANT
    if (simd::has_avx2()) i = interior_avx2(xp, w, before, after, inv, o, i, last_full);
#endif
    i = interior_generic(xp, w, before, after, inv, o, i, last_full);
    for (; i < last_full; ++i) {
        double a = 0.0;
        for (long e = -before; e <= after; ++e) a += w[e] * xp[i + e];
        o[i] = a * inv;
    }
    for (; i < len; ++i) edge(i);
}

std::string_view vector_kernels() noexcept { return simd::has_avx2() ? "avx2" : "generic"; }

std::vector<double> gaussian_smooth(std::span<const double> x, int window) {
    std::vector<double> out(x.size());
    gaussian_smooth(x, window, out);
    return out;
}

}  // namespace rollsense::features
