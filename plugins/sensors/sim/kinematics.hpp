// Kinematics of the parallel fingers and of a cylinder rolling between them
// (docs/simulation.md §1).
//
// Frame: x runs along the sensing finger's contact surface, measured from the
// nominal centre of barometer 2 (positive towards barometer 3, the direction the
// object travels when the finger turns from -44° to +44°); y is normal to it,
// pointing at the pushing finger. Angles θ are the fingers' angle from the palm
// normal, in radians inside the model (the plugin converts from degrees).
#pragma once

namespace rollsense::sim {

struct HandGeometry {
    // T: sum of the distances from each finger's joint axis to its contact
    // surface (finger body, PCB, rubber), mm. Fitted (docs/simulation.md §6).
    double finger_offset_sum = 41.0;
    // Distance along a finger from its joint axis to barometer 2, mm: sets the
    // lever arm of the pushing finger's constant torque.
    double array_distance = 70.0;

    // Effective width d = W + T for an object of width W between the fingers.
    double effective_width(double object_width) const { return object_width + finger_offset_sum; }
    // Palm width that keeps the fingers parallel: w = d / cos θ.
    double palm_width(double object_width, double theta) const;
    // Where a point at sensing-finger coordinate x lies along the pushing finger,
    // measured from the pushing finger's joint (its lever arm), for a gap W:
    // u = x + L − (W + T) tan θ.
    double pushing_coordinate(double x, double object_width, double theta) const;
};

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
