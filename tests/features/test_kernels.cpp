// The vectorised kernels behind the smoothing heuristic and filter must give,
// bit for bit, what the scalar definitions give: features.csv of a dataset may
// not change with the CPU or with the kernel that ran. Exact comparisons (==)
// on purpose; the Approx checks against MATLAB and numpy are in test_smoothing.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "goertzel.hpp"
#include "rollsense/features.hpp"
#include "simd.hpp"

using namespace rollsense::features;

namespace {

std::vector<double> noise(std::size_t n, std::uint64_t s, double scale) {
    std::vector<double> out(n);
    for (auto& v : out) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        v = scale * (static_cast<double>(s >> 11) / 9007199254740992.0 - 0.5);
    }
    return out;
}

// A bump on noise, like one channel of a roll.
std::vector<double> roll_like(std::size_t n, std::uint64_t seed) {
    auto x = noise(n, seed, 0.01);
    const double centre = 0.4 * static_cast<double>(n), width = 0.08 * static_cast<double>(n) + 1.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double d = (static_cast<double>(i) - centre) / width;
        x[i] += 0.3 * std::exp(-0.5 * d * d);
    }
    return x;
}

// Goertzel's recurrence for one bin, scalar: the definition the kernels vectorise.
double one_bin(const std::vector<double>& x, std::size_t k) {
    const double n = static_cast<double>(x.size());
    const double q = 2.0 * std::cos(std::numbers::pi * static_cast<double>(k) / n);
    double s1 = 0.0, s2 = 0.0;
    for (double c : x) {
        const double s = (c - s2) + q * s1;
        s2 = s1;
        s1 = s;
    }
    return std::max(0.0, s1 * s1 + s2 * s2 - q * s1 * s2);
}

// The window heuristic one bin at a time (classifier.md §1), with Goertzel's
// recurrence per bin and the normaliser from Parseval: what the vectorised
// sweep computes, in the order the sums must keep.
int window_reference(const std::vector<double>& x, double factor) {
    const std::size_t n = x.size();
    const double tau = 1.0 - factor;
    if (n < 2 || tau >= 1.0) return 1;
    if (tau <= 0.0) return static_cast<int>(n);
    auto window = [n](std::size_t rho) {
        const double a =
            0.44294 * 2.0 * static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(rho - 1, 1));
        return static_cast<int>(std::min(std::ceil(std::sqrt(a * a + 1.0)), 2.0 * static_cast<double>(n)));
    };
    double mean = 0.0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(n);
    std::vector<double> c(n);
    double energy = 0.0, f0 = 0.0, fn = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        c[i] = x[i] - mean;
        energy += c[i] * c[i];
        f0 += c[i];
        fn += (i % 2 == 0) ? c[i] : -c[i];
    }
    const double total = (2.0 * static_cast<double>(n) * energy + f0 * f0 - fn * fn) / 2.0;
    if (!(total > 0.0)) return 1;
    double cumulative = f0 * f0;
    if (cumulative / total > tau) return window(1);
    for (std::size_t k = 1; k < n; ++k) {
        cumulative += one_bin(c, k);
        if (cumulative / total > tau) return window(k + 1);
    }
    return window(n);
}

// |F[k]|² of the 2N-point DFT, directly.
double dft_bin(const std::vector<double>& x, std::size_t k) {
    std::complex<double> f = 0.0;
    const double n = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
        f += x[i] * std::polar(1.0, -std::numbers::pi * static_cast<double>(k * i) / n);
    return std::norm(f);
}

using Kernel = void (*)(std::span<const double>, const double*, double*) noexcept;

void check_kernel(Kernel kernel, std::size_t width, const char* name) {
    for (std::size_t n : {1u, 2u, 3u, 7u, 16u, 17u, 106u, 139u, 207u, 1000u}) {
        const auto x = noise(n, 11 + n, 1.0);
        const double* q = goertzel::coefficients(n, n + width);
        for (std::size_t k0 = 0; k0 < n; k0 += width) {
            double got[goertzel::kMaxBinsPerPass];
            kernel(x, q + k0, got);
            for (std::size_t j = 0; j < width; ++j) {
                INFO(name << ": n " << n << ", bin " << k0 + j);
                REQUIRE(got[j] == one_bin(x, k0 + j));
            }
        }
    }
}

// The filter's definition, scalar: interior Σ g·x times 1/Σg, edges Σ g·x / Σ g
// over the offsets inside, sums in ascending offset order.
std::vector<double> smooth_reference(const std::vector<double>& x, int window) {
    if (window < 2) return x;
    const long before = window / 2, after = (window + 1) / 2 - 1, len = static_cast<long>(x.size());
    const double sigma = window / 5.0;
    std::vector<double> g;
    double full = 0.0;
    for (long e = -before; e <= after; ++e) {
        g.push_back(std::exp(-static_cast<double>(e * e) / (2.0 * sigma * sigma)));
        full += g.back();
    }
    const double inv = 1.0 / full;
    std::vector<double> y(x.size());
    for (long i = 0; i < len; ++i) {
        const bool inside = i >= before && i + after < len;
        double num = 0.0, den = 0.0;
        for (long e = -before; e <= after; ++e) {
            if (i + e < 0 || i + e >= len) continue;
            num += g[static_cast<std::size_t>(e + before)] * x[static_cast<std::size_t>(i + e)];
            den += g[static_cast<std::size_t>(e + before)];
        }
        y[static_cast<std::size_t>(i)] = inside ? num * inv : num / den;
    }
    return y;
}

}  // namespace

TEST_CASE("Goertzel coefficients are 2·cos(πk/N), cached per length", "[kernels]") {
    for (std::size_t n : {5u, 150u, 5u, 206u, 150u}) {
        const double* q = goertzel::coefficients(n, n + 16);
        for (std::size_t k = 0; k < n + 16; ++k)
            REQUIRE(q[k] == 2.0 * std::cos(std::numbers::pi * static_cast<double>(k) / static_cast<double>(n)));
    }
}

TEST_CASE("Goertzel power is the 2N-point DFT's |F[k]|²", "[kernels]") {
    const auto x = roll_like(150, 3);
    const double* q = goertzel::coefficients(x.size(), 16);
    double p[goertzel::kMaxBinsPerPass];
    goertzel::power_generic(x, q, p);
    for (std::size_t k = 0; k < 8; ++k) CHECK(p[k] == Approx(dft_bin(x, k)).epsilon(1e-9));
}

TEST_CASE("generic Goertzel kernel equals the one-bin recurrence bit for bit", "[kernels]") {
    CHECK(goertzel::bins_per_pass() == (simd::has_avx2() ? 16u : 8u));
    CHECK(vector_kernels() == (simd::has_avx2() ? "avx2" : "generic"));
    check_kernel(&goertzel::power_generic, 8, "generic");
}

TEST_CASE("AVX2 Goertzel kernel equals the one-bin recurrence bit for bit", "[kernels]") {
    if (!simd::has_avx2()) {
        WARN("no AVX2 on this CPU (or ROLLSENSE_SIMD=generic): AVX2 kernel not checked");
        return;
    }
    check_kernel(&goertzel::power_avx2, 16, "avx2");
}

TEST_CASE("smoothing_window equals the one-bin-at-a-time heuristic", "[kernels]") {
    // Degenerate columns: constant, one sample, empty, a NaN among the data.
    auto with_nan = roll_like(150, 9);
    with_nan[40] = std::numeric_limits<double>::quiet_NaN();
    for (const auto& x : {std::vector<double>(150, 0.2), std::vector<double>{0.3}, std::vector<double>{}, with_nan})
        CHECK(smoothing_window(x, 0.05) == 1);
    for (std::size_t n : {2u, 3u, 9u, 40u, 106u, 139u, 150u, 206u, 207u, 600u}) {
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            // Bumps (small ρ) and plain noise (ρ near N: many passes).
            const auto x = seed % 3 == 0 ? noise(n, seed, 1.0) : roll_like(n, seed);
            for (double factor : {0.01, 0.05, 0.3}) {
                INFO("n " << n << ", seed " << seed << ", factor " << factor);
                REQUIRE(smoothing_window(x, factor) == window_reference(x, factor));
            }
        }
    }
}

TEST_CASE("gaussian_smooth equals the scalar definition bit for bit", "[kernels]") {
    for (std::size_t n : {1u, 2u, 5u, 16u, 33u, 106u, 207u}) {
        const auto x = roll_like(n, 5 + n);
        for (int w : {0, 1, 2, 3, 4, 5, 8, 9, 12, 17, 31, 64, 600}) {
            const auto got = gaussian_smooth(x, w);
            const auto want = smooth_reference(x, w);
            for (std::size_t i = 0; i < n; ++i) {
                INFO("n " << n << ", window " << w << ", sample " << i);
                REQUIRE(got[i] == want[i]);
            }
        }
    }
}
