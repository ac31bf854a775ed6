// Parallel-finger kinematics and the rolling cylinder against closed forms.
#include <catch2/catch.hpp>

#include <cmath>

#include "kinematics.hpp"

using namespace rollsense::sim;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

TEST_CASE("palm width keeps the fingers parallel: w = d / cos(theta)", "[sim][kinematics]") {
    HandGeometry hand;
    hand.finger_offset_sum = 30.0;
    CHECK(hand.effective_width(18.0) == Approx(48.0));
    CHECK(hand.palm_width(18.0, 0.0) == Approx(48.0));
    // ≈ 1.39·d at ±44° (simulation.md §1)
    CHECK(hand.palm_width(18.0, 44.0 * kDeg) / 48.0 == Approx(1.390).epsilon(1e-3));
    CHECK(hand.palm_width(18.0, -44.0 * kDeg) == Approx(hand.palm_width(18.0, 44.0 * kDeg)));
}

TEST_CASE("a cylinder's contact travels 0.966 d over -44..+44 degrees", "[sim][kinematics]") {
    HandGeometry hand;
    hand.finger_offset_sum = 36.0;
    for (double diameter : {18.0, 27.0, 36.0}) {
        const double d = diameter + 36.0;
        CylinderRoll roll(hand, diameter, -25.0, -44.0 * kDeg, 0.0);
        CHECK(roll.contact(-44.0 * kDeg) == Approx(-25.0));
        CHECK(roll.contact(44.0 * kDeg) - roll.contact(-44.0 * kDeg) == Approx(0.9657 * d).epsilon(1e-4));
        // Speed along the finger is (d/2) sec²θ ω: at 0° half the fingers' relative slide rate.
        const double h = 1e-6;
        CHECK((roll.contact(h) - roll.contact(-h)) / (2 * h) == Approx(0.5 * d).epsilon(1e-6));
        // The contact moves half the relative slide S(θ) = d tan θ.
        CHECK(roll.contact(20.0 * kDeg) - roll.contact(-10.0 * kDeg) ==
              Approx(0.5 * d * (std::tan(20.0 * kDeg) - std::tan(-10.0 * kDeg))));
    }
}

TEST_CASE("the peak-interval formula of simulation.md inverts the cylinder kinematics", "[sim][kinematics]") {
    // Contact from -8 to +8 mm symmetric about 0°: tan(θ3) - tan(θ1) = 32/d with
    // θ3 = -θ1 = ωΔt/2, so d = 16 / tan(ωΔt/2).
    HandGeometry hand;
    hand.finger_offset_sum = 36.0;
    const double diameter = 27.0, d = diameter + 36.0;
    CylinderRoll roll(hand, diameter, 0.0, 0.0, 0.0);  // contact at x = 0 when θ = 0
    const double theta3 = std::atan(16.0 / d);
    CHECK(roll.contact(theta3) == Approx(8.0));
    CHECK(roll.contact(-theta3) == Approx(-8.0));
    CHECK(16.0 / std::tan(theta3) == Approx(d));
}

TEST_CASE("slip shortens a cylinder's travel proportionally", "[sim][kinematics]") {
    HandGeometry hand;
    CylinderRoll no_slip(hand, 18.0, -20.0, -44.0 * kDeg, 0.0);
    CylinderRoll slip(hand, 18.0, -20.0, -44.0 * kDeg, 0.03);
    const double full = no_slip.contact(44.0 * kDeg) + 20.0;
    CHECK(slip.contact(44.0 * kDeg) + 20.0 == Approx(0.97 * full));
}

TEST_CASE("constant torque: the pushing finger's lever arm changes as the object rolls", "[sim][kinematics]") {
    HandGeometry hand;
    hand.finger_offset_sum = 36.0;
    hand.array_distance = 70.0;
    CylinderRoll roll(hand, 18.0, -25.0, -44.0 * kDeg, 0.0);
    // u = x + L - d tan θ: the sensing contact moves forward by half the relative
    // slide d·Δtanθ, so the pushing contact moves back along its finger by the other half.
    const double d = 54.0;
    CHECK(roll.lever_arm(0.0) == Approx(roll.contact(0.0) + 70.0));
    CHECK(roll.lever_arm(-44.0 * kDeg) - roll.lever_arm(44.0 * kDeg) == Approx(0.9657 * d).epsilon(1e-3));
}
