// The `modbus` plugin's parameters: the link, the joint, and its register map.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "register_field.hpp"
#include "rollsense/hal/modbus_client.hpp"
#include "rollsense/params.hpp"

namespace rollsense::modbus {

struct JointConfig {
    hal::ModbusLink link;
    std::string name;
    std::string unit = "mm";
    double min = 0.0, max = 1.0, max_velocity = 0.0;

    // Command side (written with FC16).
    RegisterField goal;
    int command_register = -1;                 // start of a command block, -1 = write the goal alone
    std::vector<std::uint16_t> command_template;  // the block's other contents (flags, speed, force)
    int activate_register = -1;                // written once on activation
    std::vector<std::uint16_t> activate_values;
    std::vector<std::uint16_t> deactivate_values;  // the release: written on deactivate, torque off, recover
    double activate_timeout_s = 5.0;

    // State side: one read of the span covering every mapped field.
    bool state_input_registers = false;  // FC04 instead of FC03
    RegisterField position, current;
    RegisterField status;  // raw value tested with the masks below
    std::uint32_t moving_mask = 0, moving_value = 0;  // moving when (status & mask) == value, mask 0 = never
    std::uint32_t ready_mask = 0, ready_value = 0;    // activation done when (status & mask) == value
    RegisterField fault;   // raw value; non-zero (after fault_mask) = fault
    std::uint32_t fault_mask = 0xFFFFFFFF;

    bool releasable() const { return activate_register >= 0 && !deactivate_values.empty(); }
    int state_first() const;
    int state_count() const;
};

ParamSchema modbus_schema();
Result<JointConfig> parse_config(const ParamSet& params);

}  // namespace rollsense::modbus
