// The `modbus` actuator: one joint whose goal, position, status and fault live
// in Modbus registers, so a Modbus-driven device (a winch motor driver, a
// Robotiq 2F-85 gripper) can stand in for a Dynamixel joint.
//
// Per control period: one register read covering every state field, and a
// write only when the goal (or the command block) changes — a Modbus device
// holds its goal, and the link is slow (RTU at 115200 baud: ~2 ms per request).
#pragma once

#include <optional>

#include "modbus_config.hpp"
#include "rollsense/actuator.hpp"
#include "rollsense/hal/modbus_client.hpp"

namespace rollsense::modbus {

class ModbusActuator final : public Actuator {
public:
    Status on_configure(const ParamSet& params, const PluginContext& context) override;
    Status on_activate() override;
    Status on_deactivate() override;
    Status on_cleanup() override;
    Status on_recover() override;
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    std::vector<JointInfo> joints() const override;
    Status read(double time, std::span<JointState> states) override;
    Status write(double time, std::span<const JointCommand> commands) override;

private:
    struct Snapshot {
        double position = 0.0, current = 0.0;
        std::uint32_t status = 0, fault = 0;
    };
    Result<Snapshot> read_state();
    Status write_goal(double position);
    Status release(const char* why);
    std::string who() const { return "joint '" + config_.name + "' (" + config_.link.describe() + ")"; }

    JointConfig config_;
    hal::ModbusClient client_;
    std::optional<std::vector<std::uint16_t>> last_written_;
    bool active_ = false;
    bool released_ = false;  // a torque-off command released it; driving again needs a new activation
};

}  // namespace rollsense::modbus
