// smoothdata equivalence: the published window-5 example and window choices
// checked against an independent numpy-FFT implementation (reference_windows.py).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "rollsense/features/smoothing.hpp"

using namespace rollsense::features;

namespace {

// The same generator as reference_windows.py, so both sides see identical noise.
std::vector<double> lcg(std::size_t n, std::uint64_t s) {
    std::vector<double> out;
    for (std::size_t i = 0; i < n; ++i) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        out.push_back(static_cast<double>(s >> 11) / 9007199254740992.0 - 0.5);
    }
    return out;
}

std::vector<double> bump(std::size_t n, double amp, double centre, double sigma, std::uint64_t seed) {
    auto noise = lcg(n, seed);
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double d = (static_cast<double>(i) - centre) / sigma;
        x[i] = amp * std::exp(-0.5 * d * d) + 0.008 * noise[i];
    }
    return x;
}

}  // namespace

TEST_CASE("gaussian_smooth reproduces MATLAB's published smoothdata(g, 'gaussian', 5)", "[smoothing]") {
    // MATLAB Answers 406563 (R2017a): input and the output MATLAB printed (4 decimals).
    const std::vector<double> g = {0.27, -0.13, 0.3, -0.1, -0.12, -0.01, -0.21, -0.13, -0.11, -0.05, -0.26, 0.04};
    const std::vector<double> matlab = {0.1330,  0.0861,  0.0728,  -0.0039, -0.0703, -0.0971,
                                        -0.1313, -0.1338, -0.1139, -0.1154, -0.1196, -0.0715};
    const auto y = gaussian_smooth(g, 5);
    REQUIRE(y.size() == matlab.size());
    for (std::size_t i = 0; i < y.size(); ++i) {
        INFO("sample " << i + 1);
        CHECK(y[i] == Approx(matlab[i]).margin(0.5e-4));
    }
}

TEST_CASE("gaussian_smooth: hand-computed edge renormalisation and even windows", "[smoothing]") {
    // Window 2: offsets {-1, 0}, sigma 0.4, weights e^{-1/0.32} and 1.
    const double g1 = std::exp(-1.0 / 0.32);
    const std::vector<double> x = {1.0, 0.0, 0.0};
    const auto y = gaussian_smooth(x, 2);
    CHECK(y[0] == Approx(1.0));                 // only offset 0 inside: renormalised to x[0]
    CHECK(y[1] == Approx(g1 / (1.0 + g1)));     // the past sample pulls y[1] up
    CHECK(y[2] == Approx(0.0).margin(1e-15));   // the future is never looked at with w = 2
    // Window 1 and 0 are identity.
    CHECK(gaussian_smooth(x, 1) == x);
    CHECK(gaussian_smooth(x, 0) == x);
    // A constant series stays constant whatever the window (weights sum to 1).
    const std::vector<double> c(17, 2.5);
    for (double v : gaussian_smooth(c, 9)) CHECK(v == Approx(2.5));
}

TEST_CASE("smoothing_window: limits of the smoothing factor and constant data", "[smoothing]") {
    const auto x = bump(150, 0.4, 75, 12, 7);
    CHECK(smoothing_window(x, 0.0) == 1);    // tau = 1: no smoothing
    CHECK(smoothing_window(x, 1.0) == 150);  // tau = 0: window N
    const std::vector<double> flat(40, 0.3);
    CHECK(smoothing_window(flat, 0.05) == 1);
    CHECK(smoothing_window(std::vector<double>{1.0}, 0.05) == 1);
}

TEST_CASE("smoothing_window matches an independent FFT implementation", "[smoothing]") {
    // Values printed by tests/features/reference_windows.py (numpy.fft).
    const auto b = bump(150, 0.4, 75, 12, 7);
    CHECK(smoothing_window(b, 0.05) == 20);
    CHECK(smoothing_window(b, 0.25) == 34);
    CHECK(smoothing_window(b, 0.01) == 17);
    std::vector<double> ramp(40);
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = static_cast<double>(i);
    CHECK(smoothing_window(ramp, 0.05) == 4);
    // All power at the Nyquist end: rho close to N, so the window is the smallest, 2.
    std::vector<double> alt(20);
    for (std::size_t i = 0; i < alt.size(); ++i) alt[i] = (i % 2 == 0) ? 1.0 : -1.0;
    CHECK(smoothing_window(alt, 0.05) == 2);
    std::vector<double> step(60, 0.0);
    for (std::size_t i = 30; i < 60; ++i) step[i] = 1.0;
    CHECK(smoothing_window(step, 0.05) == 5);
    CHECK(smoothing_window(step, 0.5) == 27);
}

TEST_CASE("smoothing_window_shared averages the channels' cumulative spectra", "[smoothing]") {
    const auto b1 = bump(150, 0.4, 75, 12, 7);
    const auto b2 = bump(150, 0.3, 60, 5, 9);
    CHECK(smoothing_window(b2, 0.05) == 10);
    const std::vector<std::span<const double>> cols = {b1, b2};
    CHECK(smoothing_window_shared(cols, 0.05) == 12);
    // One column shared with itself is its own window.
    const std::vector<std::span<const double>> one = {b1};
    CHECK(smoothing_window_shared(one, 0.05) == 20);
}
