// The `dynamixel` plugin's parameters: schema and validated configuration.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "joint_map.hpp"
#include "rollsense/etroll_hand/hand_geometry.hpp"
#include "rollsense/hal/dynamixel/injected_fault.hpp"
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
    int bus_watchdog_ms = 500;  // 0 = off; armed at activation, 20 ms steps
    // device "emulator" only: the object between the fingers (0: none) and the
    // hand it sits in (the profile's hand geometry, share/profiles/etroll-hand.lua).
    double emulated_object_mm = etroll::kDefaultEmulatedObjectWidth;
    etroll::HandGeometry hand;
    std::vector<hal::dxl::InjectedFault> inject;  // device "emulator" only
    std::vector<JointMap> joints;
};

ParamSchema dynamixel_schema();

// Check the parallel lists against each other and build the joint maps.
// Errors start "WHERE.KEY: " (the kernel's form for a profile's parameter,
// e.g. "/x/etroll.lua: devices.hand.params.max: "), then name the joint and the fix.
Result<BusConfig> parse_config(const ParamSet& params, const std::string& where = "params");

}  // namespace rollsense::dynamixel
