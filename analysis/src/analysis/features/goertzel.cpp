#include "goertzel.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "simd.hpp"

namespace rollsense::features::goertzel {
namespace {

// `Count` vectors of `V`: lanes<V>·Count bins in one pass over x. Each
// recurrence's critical path is one multiply and one add per sample; with
// Count independent vectors in flight the pass runs at the throughput of the
// FP units instead of that latency. (x − s2) is formed first, as in the scalar
// definition, and stays off the critical path.
template <class V, int Count>
[[gnu::always_inline]] inline void pass(std::span<const double> x, const double* q, double* power) {
    constexpr std::size_t L = simd::lanes<V>;
    V qv[Count], s1[Count], s2[Count];
#pragma GCC unroll 8
    for (int v = 0; v < Count; ++v) {
        simd::load(qv[v], q + L * static_cast<std::size_t>(v));
        s1[v] = V{};
        s2[v] = V{};
    }
    for (const double c : x) {
#pragma GCC unroll 8
        for (int v = 0; v < Count; ++v) {
            const V s = (c - s2[v]) + qv[v] * s1[v];
            s2[v] = s1[v];
            s1[v] = s;
        }
    }
    double raw[L * Count];
#pragma GCC unroll 8
    for (int v = 0; v < Count; ++v)
        simd::store(raw + L * static_cast<std::size_t>(v), s1[v] * s1[v] + s2[v] * s2[v] - qv[v] * s1[v] * s2[v]);
    for (std::size_t j = 0; j < L * Count; ++j) power[j] = std::max(0.0, raw[j]);
}

// A few series lengths per thread: a dataset's trials have a handful of
// lengths (one or two per rolling speed), often interleaved.
struct CoefficientCache {
    static constexpr std::size_t kSlots = 8;
    std::size_t n[kSlots] = {};
    std::vector<double> q[kSlots];
    std::size_t next = 0;  // slot replaced next (round robin)

    std::vector<double>& slot(std::size_t len) {
        for (std::size_t i = 0; i < kSlots; ++i)
            if (n[i] == len) return q[i];
        const std::size_t i = next;
        next = (next + 1) % kSlots;
        n[i] = len;
        q[i].clear();
        return q[i];
    }
};
thread_local CoefficientCache tl_cache;

}  // namespace

void power_generic(std::span<const double> x, const double* q, double* power) noexcept {
    pass<simd::Vec2, 4>(x, q, power);
}

#if ROLLSENSE_HAVE_AVX2_VARIANT
// 4 × 4 lanes: 8 state, 4 coefficient and 1 sample register of the 16 YMM.
ROLLSENSE_TARGET_AVX2 void power_avx2(std::span<const double> x, const double* q, double* power) noexcept {
    pass<simd::Vec4, 4>(x, q, power);
}
#else
void power_avx2(std::span<const double> x, const double* q, double* power) noexcept {
    // Never selected off x86 (has_avx2() is false); kept for a uniform interface.
    power_generic(x, q, power);
    power_generic(x, q + 8, power + 8);
}
#endif

std::size_t bins_per_pass() noexcept { return simd::has_avx2() ? 16 : 8; }

void power(std::span<const double> x, const double* q, double* out) noexcept {
    if (simd::has_avx2()) power_avx2(x, q, out);
    else power_generic(x, q, out);
}

const double* coefficients(std::size_t n, std::size_t count) {
    std::vector<double>& q = tl_cache.slot(n);
    const double nd = static_cast<double>(n);
    // The same expression as the one-bin definition, so the values are identical.
    for (std::size_t k = q.size(); k < count; ++k)
        q.push_back(2.0 * std::cos(std::numbers::pi * static_cast<double>(k) / nd));
    return q.data();
}

}  // namespace rollsense::features::goertzel
