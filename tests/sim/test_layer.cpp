// The rubber layer's response and the contact-load shapes.
#include <catch2/catch.hpp>

#include <cmath>

#include "contact_load.hpp"
#include "layer_response.hpp"

using namespace rollsense::sim;

namespace {
double numeric_fwhm(const LayerKernel& k) {
    const double half = 0.5 * k.line(0.0);
    double lo = 0.0, hi = 50.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (k.line(mid) > half ? lo : hi) = mid;
    }
    return 2.0 * lo;
}
}  // namespace

TEST_CASE("layer response is symmetric, integrates to one and has the configured FWHM", "[sim][layer]") {
    for (double fwhm : {3.7, 4.5, 6.0}) {
        INFO("fwhm " << fwhm);
        const LayerKernel pure(fwhm, 0.0, 8.0, 4.0);
        CHECK(numeric_fwhm(pure) == Approx(fwhm).epsilon(1e-6));
        const LayerKernel k(fwhm, 0.015, 8.0, 4.0);
        double integral = 0.0;
        for (double u = -100.0; u < 100.0; u += 0.01) {
            CHECK(k.line(u) == Approx(k.line(-u)).epsilon(1e-12));
            integral += k.line(u + 0.005) * 0.01;
        }
        CHECK(integral == Approx(1.0).epsilon(1e-4));  // equilibrium: the board carries the whole load
        // The weak tail: 1.5 % of the peak one pitch away (beside what is left of
        // the core there), and it barely widens the core.
        const double core_at_pitch = (1.0 - k.tail_weight()) * pure.line(8.0);
        CHECK((k.line(8.0) - core_at_pitch) / k.line(0.0) == Approx(0.015).epsilon(1e-9));
        CHECK(numeric_fwhm(k) == Approx(fwhm).epsilon(0.05));
    }
}

TEST_CASE("the 3.5 mm layer's physical core: peak about 0.82 F/h at FWHM 1.05 h", "[sim][layer]") {
    const double h = 3.5;
    const LayerKernel k(1.05 * h, 0.0, 8.0, 4.0);
    CHECK(k.line(0.0) * h == Approx(0.82).epsilon(0.1));
}

TEST_CASE("a spread load widens the core as a Gaussian of the summed variances", "[sim][layer]") {
    const LayerKernel k(4.5, 0.0, 8.0, 4.0);
    const LayerKernel wider(2.3548200450309493 * std::sqrt(k.sigma() * k.sigma() + 1.0), 0.0, 8.0, 4.0);
    for (double u : {0.0, 1.0, 3.0, 7.0}) CHECK(k.spread(u, 1.0) == Approx(wider.line(u)).epsilon(1e-12));
    CHECK(k.spread(2.0, 0.0) == Approx(k.line(2.0)));
}

TEST_CASE("a linear pressure segment matches numerical integration of the line response", "[sim][layer]") {
    const LayerKernel k(4.5, 0.0, 8.0, 4.0);  // the core is exact
    const double u0 = -3.0, u1 = 6.0, p0 = 0.02, p1 = 0.005;
    for (double x : {-10.0, -3.0, 0.0, 2.5, 8.0, 14.0}) {
        double numeric = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            const double xi = u0 + (u1 - u0) * (i + 0.5) / n;
            numeric += (p0 + (p1 - p0) * (xi - u0) / (u1 - u0)) * k.line(x - xi) * (u1 - u0) / n;
        }
        CHECK(k.linear_segment(x, u0, u1, p0, p1) == Approx(numeric).epsilon(1e-6).margin(1e-12));
    }
}

TEST_CASE("a uniform segment including the tail matches numerical integration", "[sim][layer]") {
    const LayerKernel k(4.5, 0.015, 8.0, 4.0);
    for (double x : {-9.0, 0.0, 4.0, 12.0}) {
        double numeric = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) numeric += 0.01 * k.line(x - (-6.5 + 13.0 * (i + 0.5) / n)) * 13.0 / n;
        CHECK(k.linear_segment(x, -6.5, 6.5, 0.01, 0.01) == Approx(numeric).epsilon(1e-6));
    }
}

TEST_CASE("a flat face gives a plateau about 0.96 F/a, an edge peaks 3-4x higher", "[sim][layer]") {
    const LayerKernel k(4.5, 0.015, 8.0, 4.0);
    const double F = 0.03;
    for (double a : {13.0, 18.0}) {
        const double face = k.linear_segment(0.0, -a / 2, a / 2, F / a, F / a);
        CHECK(face / (F / a) == Approx(0.96).margin(0.05));
        const double edge = F * k.line(0.0);
        CHECK(edge / face > 2.3);
        CHECK(edge / face < 4.2);
    }
}

TEST_CASE("Hertz half-width grows with the square root of diameter and load", "[sim][layer]") {
    const double b = hertz_half_width(0.03, 9.0, 0.3);
    CHECK(b == Approx(std::sqrt(4 * 0.03 * 9.0 / (3.14159265358979323846 * 0.3))));
    CHECK(hertz_half_width(0.03, 18.0, 0.3) / b == Approx(std::sqrt(2.0)));
    CHECK(hertz_half_width(0.12, 9.0, 0.3) / b == Approx(2.0));
    CHECK(b > 0.9);
    CHECK(b < 1.5);  // 1-1.4 mm for these diameters (simulation.md §2)
}

TEST_CASE("Winkler pivot load: forces add up, a steep edge is narrow, a flat face is uniform", "[sim][layer]") {
    const double F = 0.03, k = 0.15;
    // A square's edge at 45°: two triangles of equal size.
    auto edge = winkler_pivot_load(PivotProfile{2.0, 1.0, 1.0, 9.0, 9.0}, F, k);
    CHECK(edge.segments[0].force() + edge.segments[1].force() == Approx(F));
    CHECK(edge.segments[0].force() == Approx(edge.segments[1].force()));
    CHECK(edge.segments[1].u1 - edge.segments[0].u0 < 2.0);
    CHECK(edge.depth == Approx(std::sqrt(F / k)));
    // A face exactly flat in front: uniform over its length.
    auto flat = winkler_pivot_load(PivotProfile{0.0, 1.0, 0.0, 9.0, 13.0}, F, k);
    CHECK(flat.segments[0].force() + flat.segments[1].force() == Approx(F));
    CHECK(flat.segments[1].p0 == Approx(flat.segments[1].p1));
    CHECK(flat.segments[1].u1 == Approx(13.0));
    // Nearly flat: spreads over the whole face as a trapezoid, heavier at the pivot.
    auto nearly = winkler_pivot_load(PivotProfile{0.0, 1.0, 1e-4, 9.0, 13.0}, F, k);
    CHECK(nearly.segments[1].u1 == Approx(13.0));
    CHECK(nearly.segments[1].p0 > nearly.segments[1].p1);
    CHECK(nearly.segments[0].force() + nearly.segments[1].force() == Approx(F));
    // Tilted a few degrees: a triangle that does not reach the far edge.
    auto tilted = winkler_pivot_load(PivotProfile{0.0, 1.0, std::tan(0.1), 9.0, 13.0}, F, k);
    CHECK(tilted.segments[1].u1 < 13.0);
    CHECK(tilted.segments[1].p1 == Approx(0.0).margin(1e-15));
    CHECK(tilted.segments[0].force() + tilted.segments[1].force() == Approx(F));
}

TEST_CASE("the two-face pivot response equals its two segments", "[sim][layer]") {
    const LayerKernel k(4.5, 0.015, 8.0, 4.0);
    for (double x : {-8.0, -1.0, 0.0, 3.0, 8.0})
        CHECK(k.two_segments(x, -2.0, 0.5, 4.0, 0.0, 0.02, 0.004) ==
              Approx(k.linear_segment(x, -2.0, 0.5, 0.0, 0.02) + k.linear_segment(x, 0.5, 4.0, 0.02, 0.004)).epsilon(1e-12));
}
