#include "rollsense/etroll_hand/hand_geometry.hpp"

#include <cmath>

namespace rollsense::etroll {

double HandGeometry::palm_width(double object_width, double theta) const {
    return effective_width(object_width) / std::cos(theta);
}

double HandGeometry::pushing_coordinate(double x, double object_width, double theta) const {
    return x + array_distance - effective_width(object_width) * std::tan(theta);
}

ParamSchema hand_geometry_params() {
    const HandGeometry d;  // the defaults live in one place: HandGeometry
    return {
        param_number("finger_offset_sum", d.finger_offset_sum,
                     "hand geometry: T, joint axis to contact surface, both fingers summed (fitted)", 0.0, 200.0,
                     "mm"),
        param_number("array_distance", d.array_distance,
                     "hand geometry: along a finger from its joint to barometer 2 (the pushing finger's lever arm)",
                     10.0, 300.0, "mm"),
    };
}

HandGeometry hand_geometry_from(const ParamSet& params) {
    HandGeometry g;
    g.finger_offset_sum = params.get_number("finger_offset_sum");
    g.array_distance = params.get_number("array_distance");
    return g;
}

}  // namespace rollsense::etroll
