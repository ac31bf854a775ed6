// The E-TRoll hand's geometry: the one home of its numbers. The defaults are
// the simulation's calibrated values (docs/simulation.md §6); a profile sets
// them for every device at once through share/profiles/etroll-hand.lua, and
// rollsense-dxl-emu takes them from its flags.
//
// Angles θ are the fingers' angle from the palm normal, in radians.
#pragma once

#include "rollsense/params.hpp"

namespace rollsense::etroll {

struct HandGeometry {
    // T: sum of the distances from each finger's joint axis to its contact
    // surface (finger body, PCB, rubber), mm. Fitted (docs/simulation.md §6).
    double finger_offset_sum = 42.0;
    // Distance along a finger from its joint axis to barometer 2, mm: the lever
    // arm of the pushing finger's constant torque, and where it meets the object.
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

// The width between the fingers of the object the emulator clamps when it is
// told no other, mm: the mean flat width of the paper's nine objects (Table
// II), so that d = 24 mm + T sits in the middle of the stock set.
inline constexpr double kDefaultEmulatedObjectWidth = 24.0;

// The geometry as plugin parameters (finger_offset_sum, array_distance, in
// mm), the same names, ranges and defaults in every plugin that takes them, so
// one table in a profile (share/profiles/etroll-hand.lua) sets them all.
ParamSchema hand_geometry_params();
HandGeometry hand_geometry_from(const ParamSet& params);

}  // namespace rollsense::etroll
