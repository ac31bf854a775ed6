// How one joint of the hand maps onto one servo: servo degrees <-> joint
// units (degrees, or millimetres through a pinion or drum radius), the joint's
// offset, and the per-model current unit.
//
//   joint = k * servo_deg + offset,  k = 1 for a revolute joint,
//   k = ratio * radius * pi / 180 for a linear one (mm per servo degree).
// The palm's double rack and pinion moves both jaws, so its width changes by
// 2 * r * theta: ratio 2. The winch pays out r * theta of string: ratio 1.
#pragma once

#include <cstdint>
#include <string>

#include "rollsense/hal/dynamixel/control_table.hpp"
#include "rollsense/types.hpp"

namespace rollsense::dynamixel {

struct JointMap {
    std::string name;
    std::uint8_t id = 1;
    const hal::dxl::ModelInfo* model = nullptr;
    std::string unit = "deg";  // "deg" or "mm"
    double radius_mm = 0.0;    // 0 for a revolute joint
    double ratio = 1.0;
    double offset = 0.0;       // joint units
    double min = -180.0, max = 180.0;  // joint units
    double max_current_ma = 0.0;       // 0 = the model's largest Current Limit
    double max_velocity = 0.0;         // joint units/s, 0 = the servo's Velocity Limit
    ControlMode default_mode = ControlMode::position;

    // Joint units per servo degree.
    double scale() const;

    double ticks_to_joint(double ticks) const;
    std::int32_t joint_to_ticks(double position) const;
    double velocity_units_to_joint(double units) const;      // unit/s
    std::int32_t joint_to_velocity_units(double velocity) const;  // rounds, keeps sign
    // Profile values: a velocity is never 0 (the servo's "no limit"): 0 (the
    // device's maximum) is max_velocity, else the model's factory Velocity
    // Limit; any positive value is at least 1 unit, so a slow command never
    // turns into "no limit". An acceleration of 0 stays 0 (no limit).
    std::uint32_t joint_to_profile_velocity(double velocity) const;
    std::uint32_t joint_to_profile_acceleration(double acceleration) const;
    double current_units_to_ma(double units) const;
    std::int32_t ma_to_current_units(double ma) const;
    // The servo's Current Limit in units for this joint.
    std::uint16_t current_limit_units() const;
};

hal::dxl::OperatingMode to_operating_mode(ControlMode mode);
ControlMode to_control_mode(hal::dxl::OperatingMode mode);

}  // namespace rollsense::dynamixel
