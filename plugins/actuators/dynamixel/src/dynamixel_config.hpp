// The `dynamixel` plugin's parameters: schema and validated configuration.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "joint_map.hpp"
#include "rollsense/params.hpp"
#include "rollsense/status.hpp"

namespace rollsense::dynamixel {

struct BusConfig {
    std::string device;
    std::uint32_t baud = 57600;
    int retries = 3;
    std::chrono::microseconds timeout{std::chrono::milliseconds(30)};
    bool write_position_limits = true;
    bool torque_off_on_deactivate = true;
    double emulated_object_mm = 65.0;  // device "emulator" only
    std::vector<JointMap> joints;
};

ParamSchema dynamixel_schema();

// Check the parallel lists against each other and build the joint maps.
// Errors name the parameter and the joint.
Result<BusConfig> parse_config(const ParamSet& params);

}  // namespace rollsense::dynamixel
