#include "modbus_actuator.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "rollsense/log.hpp"

namespace rollsense::modbus {

Status ModbusActuator::on_configure(const ParamSet& params, const PluginContext& context) {
    (void)context;
    auto cfg = parse_config(params);
    if (!cfg.ok()) return cfg.status();
    config_ = std::move(cfg).value();
    auto client = hal::ModbusClient::connect(config_.link);
    if (!client.ok()) return client.status();
    client_ = std::move(client).value();
    last_written_.reset();
    // Reading once proves the register map and the slave id are right.
    auto s = read_state();
    if (!s.ok()) return s.status();
    return {};
}

std::vector<JointInfo> ModbusActuator::joints() const {
    JointInfo j;
    j.name = config_.name;
    j.unit = config_.unit;
    j.min_position = config_.min;
    j.max_position = config_.max;
    j.max_velocity = config_.max_velocity;
    j.max_current = 0.0;
    j.modes = {ControlMode::position};
    return {j};
}

Result<ModbusActuator::Snapshot> ModbusActuator::read_state() {
    const int first = config_.state_first();
    const int count = config_.state_count();
    auto regs = config_.state_input_registers ? client_.read_input(first, count) : client_.read_holding(first, count);
    if (!regs.ok()) return Error{regs.error().code, "joint '" + config_.name + "': " + regs.error().message};
    Snapshot s;
    s.position = config_.position.decode(*regs, first);
    if (config_.status.mapped()) s.status = static_cast<std::uint32_t>(config_.status.decode_raw(*regs, first));
    if (config_.fault.mapped()) s.fault = static_cast<std::uint32_t>(config_.fault.decode_raw(*regs, first));
    if (config_.current.mapped()) s.current = config_.current.decode(*regs, first);
    return s;
}

Status ModbusActuator::write_goal(double position) {
    auto raw = config_.goal.to_raw(position);
    if (!raw)
        return {ErrorCode::limit_violation, who() + ": goal " + std::to_string(position) + " " + config_.unit +
                                                " does not fit the goal register's format"};
    std::vector<std::uint16_t> block;
    int start = config_.goal.address;
    if (config_.command_register >= 0) {
        block = config_.command_template;
        start = config_.command_register;
    } else {
        block.assign(static_cast<std::size_t>(register_count(config_.goal.format)), 0);
    }
    config_.goal.encode_raw(*raw, block, start);
    if (last_written_ && *last_written_ == block) return {};
    if (auto st = client_.write_registers(start, block); !st.ok())
        return {st.code(), "joint '" + config_.name + "': " + st.message()};
    last_written_ = block;
    return {};
}

Status ModbusActuator::on_activate() {
    if (!client_.is_open()) return {ErrorCode::state_error, who() + ": not connected (configure first)"};
    auto s = read_state();
    if (!s.ok()) return s.status();
    if (config_.fault.mapped() && (s->fault & config_.fault_mask))
        return {ErrorCode::hardware_fault, who() + ": the device reports fault code " + std::to_string(s->fault) +
                                               "; clear it on the device before activating"};
    // Hold here: the goal becomes the present position before anything that
    // enables motion is written.
    const double here = std::clamp(s->position, config_.min, config_.max);
    last_written_.reset();
    released_ = false;
    if (config_.command_register < 0)
        if (auto st = write_goal(here); !st.ok()) return st;
    if (config_.activate_register >= 0) {
        if (auto st = client_.write_registers(config_.activate_register, config_.activate_values); !st.ok())
            return {st.code(), "joint '" + config_.name + "': activation: " + st.message()};
        if (config_.ready_mask) {
            const auto deadline = std::chrono::steady_clock::now() +
                                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(config_.activate_timeout_s));
            for (;;) {
                auto now_state = read_state();
                if (!now_state.ok()) return now_state.status();
                if ((now_state->status & config_.ready_mask) == config_.ready_value) break;
                if (std::chrono::steady_clock::now() > deadline)
                    return {ErrorCode::timeout, who() + ": not ready " + std::to_string(config_.activate_timeout_s) +
                                                    " s after activation (status " +
                                                    std::to_string(now_state->status) + ")"};
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            }
        }
    }
    if (config_.command_register >= 0)
        if (auto st = write_goal(here); !st.ok()) return st;
    active_ = true;
    return {};
}

// The device's own "let go": the profile's deactivate_values written to the
// activation register (a Robotiq 2F-85 drops rACT and rGTO and stops). The
// one place that writes them: deactivate, a torque-off command, recover.
Status ModbusActuator::release(const char* why) {
    if (!config_.releasable() || !client_.is_open()) return {};
    last_written_.reset();  // the release may overwrite the command block
    if (auto st = client_.write_registers(config_.activate_register, config_.deactivate_values); !st.ok())
        return {st.code(), "joint '" + config_.name + "': " + why + ": " + st.message()};
    return {};
}

Status ModbusActuator::on_deactivate() {
    active_ = false;
    return release("deactivation");
}

Status ModbusActuator::on_cleanup() {
    client_.close();
    last_written_.reset();
    return {};
}

// The failure that brought the device here was reported already; a device
// still driving its last goal is released if it answers (within the link's
// timeout and retries), and one that does not is reported, not waited for.
Status ModbusActuator::on_recover() {
    active_ = false;
    if (auto st = release("release on recover"); !st.ok())
        log_warning("modbus", st.message() + "; the device may still hold or drive its last goal");
    return on_cleanup();
}

Status ModbusActuator::read(double time, std::span<JointState> states) {
    (void)time;
    if (states.size() != 1) return {ErrorCode::invalid_argument, "read() expects 1 state, got " + std::to_string(states.size())};
    auto s = read_state();
    if (!s.ok()) return s.status();
    auto& st = states[0];
    st.position = s->position;
    st.velocity = 0.0;  // not mapped: a register device rarely reports it
    st.current = s->current;
    st.moving = config_.moving_mask != 0 && (s->status & config_.moving_mask) == config_.moving_value;
    st.torque_enabled = active_ && !released_;
    st.mode = ControlMode::position;
    st.fault_bits = s->fault & config_.fault_mask;
    if (st.fault_bits) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%X", st.fault_bits);
        st.fault = "device fault code " + std::string(code);
    } else {
        st.fault.clear();
    }
    return {};
}

Status ModbusActuator::write(double time, std::span<const JointCommand> commands) {
    (void)time;
    if (commands.size() != 1)
        return {ErrorCode::invalid_argument, "write() expects 1 command, got " + std::to_string(commands.size())};
    const auto& c = commands[0];
    if (c.mode != ControlMode::position)
        return {ErrorCode::unsupported, who() + ": only position mode is mapped (got " + std::string(to_string(c.mode)) + ")"};
    if (!c.torque_enabled) {  // the safe state, or a faulted joint
        if (!config_.releasable())
            return {ErrorCode::unsupported, who() + ": cannot release the joint: the profile maps no release "
                                                    "(give 'activate_register' and 'deactivate_values')"};
        if (released_) return {};
        if (auto st = release("release"); !st.ok()) return st;
        released_ = true;
        return {};
    }
    if (released_)
        return {ErrorCode::state_error, who() + ": released by a torque-off command; deactivate and activate "
                                                "the device to drive it again"};
    if (c.position < config_.min - 1e-9 || c.position > config_.max + 1e-9)
        return {ErrorCode::limit_violation, who() + ": goal " + std::to_string(c.position) + " outside [" +
                                                std::to_string(config_.min) + ", " + std::to_string(config_.max) + "]"};
    return write_goal(c.position);
}

Result<ValueMap> ModbusActuator::invoke(const std::string& verb, const ValueMap& args) {
    (void)args;
    if (verb == "registers") {
        // Raw state registers, for bringing up a new register map.
        const int first = config_.state_first();
        auto regs = config_.state_input_registers ? client_.read_input(first, config_.state_count())
                                                  : client_.read_holding(first, config_.state_count());
        if (!regs.ok()) return regs.error();
        ValueMap out;
        for (std::size_t i = 0; i < regs->size(); ++i)
            out[std::to_string(first + static_cast<int>(i))] = static_cast<std::int64_t>((*regs)[i]);
        return out;
    }
    return Error{ErrorCode::unsupported, "no operation '" + verb + "' (modbus knows: registers)"};
}

}  // namespace rollsense::modbus
