// The object between the E-TRoll fingers, as the servo emulator sees it: an
// obstacle for the pushing finger whose angle depends on the sensing finger's
// angle and the palm width. It is what lets the palm-parallel controller (and
// the Table I clamp) run against the emulator: widen the palm and the pushing
// finger, pressing on the object in current mode, swings toward the sensing
// finger's angle. The HAL's bus emulator knows servos only; this model couples
// three of them (clamp_object below).
//
// Geometry (docs/dynamixel.md, "Emulated hand"; the numbers are the hand's,
// hand_geometry.hpp): with both fingers parallel at angle θ, the palm width
// that fits an object of width W is w = d / cos θ with d = W + T. Away from
// parallel, to first order, the pushing finger meets the object at
//
//     θ_contact = θ_sensing + (w·cos θ_sensing − d) / L     [radians]
//
// where L (the array distance) is the distance from the joint axes to the
// contact along the finger: a palm that is too narrow holds the pushing finger
// open (a lower angle), a palm that is too wide lets it close past parallel.
#pragma once

#include <cstdint>
#include <numbers>

#include "rollsense/etroll_hand/hand_geometry.hpp"
#include "rollsense/hal/dynamixel/bus_emulator.hpp"

namespace rollsense::etroll {

struct ClampedObject {
    std::uint8_t sensing_id = 1;
    std::uint8_t pushing_id = 2;
    std::uint8_t palm_id = 3;
    // Palm width from the palm servo's angle: width = centre + mm_per_degree · angle
    // (the etroll profile's palm joint: radius 10 mm, ratio 2, offset 65 mm).
    double palm_mm_per_degree = 2.0 * 10.0 * std::numbers::pi / 180.0;
    double palm_centre_mm = 65.0;
    double object_width_mm = kDefaultEmulatedObjectWidth;  // W, between the fingers' surfaces
    HandGeometry hand;

    double effective_width_mm() const { return hand.effective_width(object_width_mm); }
};

// The pushing finger's angle (degrees) at which it touches the object; it can
// not move to higher angles (toward the sensing finger) than this.
double pushing_contact_degrees(const ClampedObject& object, double sensing_degrees, double palm_degrees);

// Put the object between the fingers of the hand on `bus`: from now on the bus
// re-places the pushing finger's obstacle as the sensing finger and the palm
// move. Fails, naming the missing servo, unless the three ids are on the bus.
Status clamp_object(hal::dxl::BusEmulator& bus, const ClampedObject& object);

}  // namespace rollsense::etroll
