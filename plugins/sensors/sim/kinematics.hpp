// Kinematics of the parallel fingers and of a cylinder rolling between them
// (docs/simulation.md §1).
//
// Frame: x runs along the sensing finger's contact surface, measured from the
// nominal centre of barometer 2 (positive towards barometer 3, the direction the
// object travels when the finger turns from -44° to +44°); y is normal to it,
// pointing at the pushing finger. Angles θ are the fingers' angle from the palm
// normal, in radians inside the model (the plugin converts from degrees).
#pragma once

#include "rollsense/etroll_hand/hand_geometry.hpp"

namespace rollsense::sim {

// The hand's geometry has one home, shared with the servo emulator's
// clamped object (plugins/common/etroll_hand).
using etroll::HandGeometry;

// A cylinder rolling without slip on both fingers: its contact on the sensing
// finger moves half the fingers' relative slide, s(θ) = s0 + (d/2)(tan θ − tan θ0),
// reduced by a slip fraction (the contact slides back a little).
class CylinderRoll {
public:
    CylinderRoll() = default;
    CylinderRoll(const HandGeometry& hand, double diameter, double start_contact, double start_theta,
                 double slip_fraction);

    double contact(double theta) const;        // s(θ), mm
    double lever_arm(double theta) const;      // pushing finger's contact from its joint, mm
    double effective_width() const { return d_; }
    double diameter() const { return diameter_; }

private:
    HandGeometry hand_;
    double diameter_ = 18.0;
    double d_ = 54.0;
    double s0_ = 0.0;
    double tan0_ = 0.0;
    double travel_factor_ = 1.0;
};

}  // namespace rollsense::sim
