// The object between the E-TRoll fingers, as the servo emulator sees it: an
// obstacle for the pushing finger whose angle depends on the sensing finger's
// angle and the palm width. It is what lets the palm-parallel controller (and
// the Table I clamp) run against the emulator: widen the palm and the pushing
// finger, pressing on the object in current mode, swings toward the sensing
// finger's angle.
//
// Geometry (docs/dynamixel.md, "Emulated hand"): with both fingers parallel at
// angle θ, the palm width that fits an object of effective width d (object
// width plus both fingers' joint-to-surface distances) is w = d / cos θ. Away
// from parallel, to first order, the pushing finger meets the object at
//
//     θ_contact = θ_sensing + (w·cos θ_sensing − d) / L     [radians]
//
// where L is the distance from the joint axes to the contact along the finger:
// a palm that is too narrow holds the pushing finger open (a lower angle), a
// palm that is too wide lets it close past parallel.
#pragma once

#include <cstdint>

namespace rollsense::hal::dxl {

struct ClampedObject {
    std::uint8_t sensing_id = 1;
    std::uint8_t pushing_id = 2;
    std::uint8_t palm_id = 3;
    // Palm width from the palm servo's angle: width = centre + mm_per_degree · angle
    // (the etroll profile's radius 10 mm, ratio 2, offset 65 mm).
    double palm_mm_per_degree = 2.0 * 10.0 * 3.14159265358979323846 / 180.0;
    double palm_centre_mm = 65.0;
    double effective_width_mm = 65.0;  // d: parallel at θ = 0 with the palm at its centre
    double lever_mm = 60.0;            // L: joint axes to the contact, along the finger
};

// The pushing finger's angle (degrees) at which it touches the object; it can
// not move to higher angles (toward the sensing finger) than this.
double pushing_contact_degrees(const ClampedObject& object, double sensing_degrees, double palm_degrees);

}  // namespace rollsense::hal::dxl
