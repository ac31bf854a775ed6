// Tumbling prisms: step length = edge length, one pivot per Δ(tan θ) = 2a/d,
// no edge ever inside a finger, and the face dwell.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "polygon_tumbling.hpp"

using namespace rollsense::sim;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

struct Pivot {
    double contact;
    double theta;
    double gap;
};

// Roll -44° → +44° in small steps and note each new sensing pivot.
std::vector<Pivot> roll_and_record(PolygonTumbler& t, double& worst_penetration) {
    std::vector<Pivot> pivots;
    int last = -1;
    worst_penetration = -1.0;
    for (int i = 0; i <= 8800; ++i) {
        const double theta = (-44.0 + 0.01 * i) * kDeg;
        t.advance(theta);
        worst_penetration = std::max(worst_penetration, t.max_penetration());
        if (t.sensing_pivot() != last) {
            last = t.sensing_pivot();
            pivots.push_back({t.contact().contact, t.theta(), t.contact().gap});
        }
    }
    return pivots;
}
}  // namespace

TEST_CASE("sharp prisms step forward by exactly one edge length per pivot", "[sim][polygon]") {
    HandGeometry hand;
    hand.finger_offset_sum = 36.0;
    for (int sides : {4, 5, 6}) {
        for (double a : {13.0, 18.0}) {
            INFO(sides << " sides, a = " << a);
            PolygonShape shape{sides, a, std::vector<double>(static_cast<std::size_t>(sides), 0.0)};
            PolygonTumbler t(hand, shape, -25.0, PolygonTumbler::flat_orientation(sides) + 1e-4, -44.0 * kDeg);
            double worst = 0.0;
            const auto pivots = roll_and_record(t, worst);
            REQUIRE(pivots.size() >= 3);
            for (std::size_t i = 1; i < pivots.size(); ++i)
                CHECK(pivots[i].contact - pivots[i - 1].contact == Approx(a).margin(1e-6));
            CHECK(worst < 1e-6);  // no edge ever inside a finger
        }
    }
}

TEST_CASE("a square pivots once per relative slide of 2a", "[sim][polygon]") {
    // Both contacts stay put during a pivot while the top one goes from behind
    // to ahead of the bottom one: the fingers slide by 2a relative to each other,
    // i.e. Δ(tan θ) = 2a/d with d = a + T at both face-flat ends.
    HandGeometry hand;
    hand.finger_offset_sum = 36.0;
    const double a = 13.0;
    PolygonShape shape{4, a, {0.0, 0.0, 0.0, 0.0}};
    PolygonTumbler t(hand, shape, -25.0, PolygonTumbler::flat_orientation(4) + 1e-4, -44.0 * kDeg);
    double worst = 0.0;
    roll_and_record(t, worst);
    // Faces land on both fingers at once (the tiny start tilt separates them by
    // a hair): keep one landing per face-flat moment.
    std::vector<Landing> l;
    for (const auto& x : t.landing_log())
        if (l.empty() || std::tan(x.theta) - std::tan(l.back().theta) > 1e-3) l.push_back(x);
    REQUIRE(l.size() >= 3);
    for (std::size_t i = 1; i < l.size(); ++i) {
        CHECK(l[i].gap == Approx(a).margin(1e-5));
        CHECK(l[i].mu_tip == Approx(1.0).margin(1e-3));  // a square needs μ >= 1 to tip
        CHECK(std::tan(l[i].theta) - std::tan(l[i - 1].theta) == Approx(2.0 * a / (a + 36.0)).epsilon(1e-4));
    }
}

TEST_CASE("the gap between the fingers follows the prism's width", "[sim][polygon]") {
    HandGeometry hand;
    const double a = 13.0;
    PolygonShape shape{6, a, std::vector<double>(6, 0.0)};
    PolygonTumbler t(hand, shape, -25.0, PolygonTumbler::flat_orientation(6) + 1e-4, -44.0 * kDeg);
    double hi = 0.0;
    for (int i = 0; i <= 8800; ++i) {
        t.advance((-44.0 + 0.01 * i) * kDeg);
        hi = std::max(hi, t.contact().gap);
    }
    // hexagon: a√3 (face to face, at every landing) to 2a (edge to edge, mid-pivot)
    REQUIRE(t.landing_log().size() >= 2);
    for (const auto& l : t.landing_log()) {
        CHECK(l.gap == Approx(std::sqrt(3.0) * a).margin(1e-5));
        CHECK(l.mu_tip == Approx(1.0 / std::sqrt(3.0)).margin(1e-4));  // 0.58 (simulation.md §1)
    }
    CHECK(hi == Approx(2.0 * a).margin(1e-2));
}

TEST_CASE("a pentagon needs mu >= 0.33 to tip", "[sim][polygon]") {
    HandGeometry hand;
    PolygonShape shape{5, 13.0, std::vector<double>(5, 0.0)};
    PolygonTumbler t(hand, shape, -25.0, PolygonTumbler::flat_orientation(5) + 1e-4, -44.0 * kDeg);
    for (int i = 0; i <= 880; ++i) t.advance((-44.0 + 0.1 * i) * kDeg);
    REQUIRE(t.landing_log().size() >= 2);
    for (const auto& l : t.landing_log()) CHECK(l.mu_tip == Approx(0.325).margin(2e-3));
}

TEST_CASE("a rounded edge rolls: the contact moves by r * dpsi during a pivot", "[sim][polygon]") {
    HandGeometry hand;
    const double r = 1.0;
    PolygonShape shape{4, 13.0, {r, r, r, r}};
    PolygonTumbler t(hand, shape, -25.0, PolygonTumbler::flat_orientation(4) + 1e-4, -44.0 * kDeg);
    t.advance(-43.9 * kDeg);
    const int pivot = t.sensing_pivot();
    const double c0 = t.contact().contact, psi0 = t.orientation();
    t.advance(-35.0 * kDeg);
    REQUIRE(t.sensing_pivot() == pivot);
    CHECK(t.contact().contact - c0 == Approx(-r * (t.orientation() - psi0)).epsilon(1e-9));
    CHECK(t.orientation() < psi0);  // tips forward (clockwise)
}

TEST_CASE("a landed face dwells flat for dwell * mu_tip of finger slide", "[sim][polygon]") {
    HandGeometry hand;
    hand.finger_offset_sum = 36.0;
    const double a = 13.0;
    PolygonShape shape{4, a, {0.0, 0.0, 0.0, 0.0}};
    PolygonTumbler plain(hand, shape, -25.0, PolygonTumbler::flat_orientation(4) + 1e-4, -44.0 * kDeg);
    PolygonTumbler dwelling(hand, shape, -25.0, PolygonTumbler::flat_orientation(4) + 1e-4, -44.0 * kDeg);
    dwelling.set_dwell(2.0, 0.0, nullptr);
    double worst = 0.0;
    const auto p_plain = roll_and_record(plain, worst);
    const auto p_dwell = roll_and_record(dwelling, worst);
    REQUIRE(p_plain.size() >= 3);
    REQUIRE(p_dwell.size() >= 3);
    // The square's μ_tip is 1: each landing costs 2 mm of relative slide, so the
    // second landing comes later by Δ(tan θ) = 2 / (a + T).
    CHECK(std::tan(p_dwell[2].theta) - std::tan(p_dwell[1].theta) ==
          Approx(std::tan(p_plain[2].theta) - std::tan(p_plain[1].theta) + 2.0 / (a + 36.0)).epsilon(1e-3));
    // and the edge positions still step by a
    CHECK(p_dwell[2].contact - p_dwell[1].contact == Approx(a).margin(1e-6));
}

TEST_CASE("rolling back retraces the tumble", "[sim][polygon]") {
    HandGeometry hand;
    PolygonShape shape{5, 13.0, std::vector<double>(5, 0.5)};
    PolygonTumbler t(hand, shape, -25.0, PolygonTumbler::flat_orientation(5) + 0.3 * kDeg, -44.0 * kDeg);
    t.advance(-40.0 * kDeg);
    const double x_mid = t.centre_x();
    t.advance(10.0 * kDeg);
    const double x_far = t.centre_x();
    CHECK(x_far > x_mid + 13.0);
    t.advance(-40.0 * kDeg);
    CHECK(t.centre_x() == Approx(x_mid).margin(0.5));
    CHECK(t.max_penetration() < 1e-6);
}
