// How a tumbling prism loads the rubber under its pivot (docs/simulation.md §2).
//
// The rubber is treated as an elastic (Winkler) foundation of stiffness k: the
// object sinks in by δ and the pressure is k times the local penetration. Near a
// pivot the object's underside is two faces rising from the edge with slopes
// t_rear and t_front over horizontal extents ℓ_rear and ℓ_front (up to the
// next edges). The pressure is then a triangle on each side while the face is
// steep, and spreads over the whole face as the face comes flat — the same
// model gives a line-like edge load, the gradual hand-over from an edge to a
// landing face, and the near-uniform plateau of a flat face.
#pragma once

#include <array>

namespace rollsense::sim {

struct PivotProfile {
    double contact = 0.0;       // x of the pivot (lowest point), mm
    double slope_rear = 1.0;    // tan of the rear face's angle to the finger (>= 0)
    double slope_front = 1.0;   // tan of the front face's angle to the finger (>= 0)
    double extent_rear = 10.0;  // horizontal length of the rear face, mm
    double extent_front = 10.0;
};

// One linear piece of the pressure distribution: p0 at u0 to p1 at u1 (N/mm²).
struct PressureSegment {
    double u0 = 0.0, u1 = 0.0, p0 = 0.0, p1 = 0.0;
    double force() const { return 0.5 * (p0 + p1) * (u1 - u0); }
};

struct PivotLoad {
    double depth = 0.0;  // δ, mm
    std::array<PressureSegment, 2> segments{};  // rear, front
};

// Pressure under a pivot for a line load F (N/mm) on a foundation of stiffness
// k (N/mm³). The two segments' forces add up to F.
PivotLoad winkler_pivot_load(const PivotProfile& profile, double line_load, double stiffness);

}  // namespace rollsense::sim
