// How a user describes an emulated bus on the command line:
//   ID:MODEL[:START_DEG[:MODE[:CONTACT_DEG]]]   e.g. "2:XM430-W350:-66:position:-40"
// MODE is position | extended_position | current | current_based_position | velocity.
#pragma once

#include <string_view>
#include <vector>

#include "rollsense/hal/dynamixel/emulated_servo.hpp"
#include "rollsense/status.hpp"

namespace rollsense::hal::dxl {

Result<ServoSetup> parse_servo_spec(std::string_view spec);
Result<OperatingMode> parse_operating_mode(std::string_view name);

// The E-TRoll bus: 1 sensing finger, 2 pushing finger, 3 palm (XM430-W350),
// 4 winch (XL330-M288, extended position), as in docs/dynamixel.md.
std::vector<ServoSetup> etroll_servos();

}  // namespace rollsense::hal::dxl
