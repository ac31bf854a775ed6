#include "modbus_config.hpp"

#include <algorithm>

namespace rollsense::modbus {

int JointConfig::state_first() const {
    int first = position.address;
    for (const auto* f : {&status, &fault, &current})
        if (f->mapped()) first = std::min(first, f->address);
    return first;
}

int JointConfig::state_count() const {
    int last = position.last_address();
    for (const auto* f : {&status, &fault, &current})
        if (f->mapped()) last = std::max(last, f->last_address());
    return last - state_first() + 1;
}

ParamSchema modbus_schema() {
    const auto& formats = format_names();
    return {
        param_string("transport", std::string("tcp"), "how the device is reached", {"tcp", "rtu"}),
        param_string("host", std::string("127.0.0.1"), "tcp: device address"),
        param_int("port", 502, "tcp: port", 1, 65535),
        param_string("device", std::string("/dev/ttyUSB0"), "rtu: serial port"),
        param_int("baud", 115200, "rtu: baud rate", 1200, 4000000, "bit/s"),
        param_string("parity", std::string("N"), "rtu: parity", {"N", "E", "O"}),
        param_int("stop_bits", 1, "rtu: stop bits", 1, 2),
        param_int("slave", 1, "Modbus slave (unit) id", 1, 247),
        param_int("timeout_ms", 100, "response timeout", 1, 10000, "ms"),
        param_int("retries", 2, "extra attempts after a timeout or a corrupted reply", 0, 10),

        param_string("name", std::nullopt, "joint name, e.g. winch or gripper"),
        param_string("unit", std::string("mm"), "joint unit", {"deg", "mm"}),
        param_number("min", std::nullopt, "lowest joint position (unit)"),
        param_number("max", std::nullopt, "highest joint position (unit)"),
        param_number("max_velocity", 0.0, "declared velocity limit (unit/s), 0 = none", 0),

        param_int("goal_register", std::nullopt, "register of the goal position", 0, 65535),
        param_string("goal_format", std::string("s32"), "packing of the goal", formats),
        param_number("goal_scale", 1.0, "joint units per goal count"),
        param_number("goal_offset", 0.0, "joint position at goal count 0"),
        param_int("command_register", -1, "first register of a command block written whole each time (-1: goal alone)", -1, 65535),
        param_int_list("command_template", std::vector<std::int64_t>{},
                       "contents of the command block (flags, speed, force); the goal is packed into it", 0, 65535),
        param_int("activate_register", -1, "register written on activation (-1: none)", -1, 65535),
        param_int_list("activate_values", std::vector<std::int64_t>{}, "values written there on activation", 0, 65535),
        param_int_list("deactivate_values", std::vector<std::int64_t>{},
                       "values written there to release the device: on deactivation, a torque-off command "
                       "(safe state) and recover",
                       0, 65535),
        param_number("activate_timeout", 5.0, "seconds to wait for the ready bits after activation", 0, 120, "s"),

        param_string("state_table", std::string("holding"), "where state registers live", {"holding", "input"}),
        param_int("position_register", std::nullopt, "register of the present position", 0, 65535),
        param_string("position_format", std::string("s32"), "packing of the present position", formats),
        param_number("position_scale", 1.0, "joint units per position count"),
        param_number("position_offset", 0.0, "joint position at position count 0"),
        param_int("status_register", -1, "status register (-1: none)", -1, 65535),
        param_string("status_format", std::string("u16"), "packing of the status", formats),
        param_int("moving_mask", 0, "status bits that tell motion (0: never moving)", 0, 4294967295.0),
        param_int("moving_value", 0, "moving when (status & moving_mask) == moving_value", 0, 4294967295.0),
        param_int("ready_mask", 0, "status bits that tell activation is complete (0: no wait)", 0, 4294967295.0),
        param_int("ready_value", 0, "ready when (status & ready_mask) == ready_value", 0, 4294967295.0),
        param_int("fault_register", -1, "fault register (-1: none)", -1, 65535),
        param_string("fault_format", std::string("u16"), "packing of the fault code", formats),
        param_int("fault_mask", std::int64_t{0xFFFFFFFF}, "fault bits; any set bit is a fault", 0, 4294967295.0),
        param_int("current_register", -1, "present current register (-1: none)", -1, 65535),
        param_string("current_format", std::string("s16"), "packing of the current", formats),
        param_number("current_scale", 1.0, "mA per current count"),
    };
}

namespace {

std::vector<std::uint16_t> words(const std::vector<std::int64_t>& v) {
    std::vector<std::uint16_t> out;
    for (auto x : v) out.push_back(static_cast<std::uint16_t>(x));
    return out;
}

Result<RegisterField> field(const ParamSet& p, const std::string& prefix, bool scaled) {
    RegisterField f;
    f.address = static_cast<int>(p.get_int(prefix + "_register"));
    auto fmt = parse_format(p.get_string(prefix + "_format"));
    if (!fmt.ok()) return Error{fmt.error().code, "'" + prefix + "_format': " + fmt.error().message};
    f.format = *fmt;
    if (scaled) {
        f.scale = p.get_number(prefix + "_scale");
        if (p.has(prefix + "_offset")) f.offset = p.get_number(prefix + "_offset");
        if (f.scale == 0.0) return Error{ErrorCode::invalid_argument, "'" + prefix + "_scale' must not be 0"};
    }
    if (f.mapped() && f.last_address() > 65535)
        return Error{ErrorCode::invalid_argument, "'" + prefix + "_register' runs past register 65535"};
    return f;
}

}  // namespace

Result<JointConfig> parse_config(const ParamSet& p) {
    JointConfig c;
    auto& l = c.link;
    l.transport = p.get_string("transport") == "rtu" ? hal::ModbusLink::Transport::rtu : hal::ModbusLink::Transport::tcp;
    l.host = p.get_string("host");
    l.port = static_cast<int>(p.get_int("port"));
    l.device = p.get_string("device");
    l.baud = static_cast<int>(p.get_int("baud"));
    l.parity = p.get_string("parity").front();
    l.stop_bits = static_cast<int>(p.get_int("stop_bits"));
    l.slave = static_cast<int>(p.get_int("slave"));
    l.timeout = std::chrono::milliseconds(p.get_int("timeout_ms"));
    l.retries = static_cast<int>(p.get_int("retries"));

    c.name = p.get_string("name");
    c.unit = p.get_string("unit");
    c.min = p.get_number("min");
    c.max = p.get_number("max");
    c.max_velocity = p.get_number("max_velocity");
    if (c.name.empty()) return Error{ErrorCode::invalid_argument, "'name' is empty"};
    if (!(c.min < c.max)) return Error{ErrorCode::invalid_argument, "'min' must be below 'max'"};

    struct Named {
        const char* prefix;
        RegisterField* out;
        bool scaled;
    };
    for (const auto& [prefix, out, scaled] : {Named{"goal", &c.goal, true}, Named{"position", &c.position, true},
                                              Named{"status", &c.status, false}, Named{"fault", &c.fault, false},
                                              Named{"current", &c.current, false}}) {
        auto f = field(p, prefix, scaled);
        if (!f.ok()) return f.error();
        *out = *f;
    }
    c.current.scale = p.get_number("current_scale");

    c.command_register = static_cast<int>(p.get_int("command_register"));
    c.command_template = words(p.get_int_list("command_template"));
    if (c.command_register >= 0) {
        const int end = c.command_register + static_cast<int>(c.command_template.size());
        if (c.command_template.empty())
            return Error{ErrorCode::invalid_argument, "'command_register' is set but 'command_template' is empty"};
        if (c.goal.address < c.command_register || c.goal.last_address() >= end)
            return Error{ErrorCode::invalid_argument,
                         "'goal_register' " + std::to_string(c.goal.address) + " lies outside the command block " +
                             std::to_string(c.command_register) + ".." + std::to_string(end - 1)};
    }
    c.activate_register = static_cast<int>(p.get_int("activate_register"));
    c.activate_values = words(p.get_int_list("activate_values"));
    c.deactivate_values = words(p.get_int_list("deactivate_values"));
    c.activate_timeout_s = p.get_number("activate_timeout");
    if (c.activate_register >= 0 && c.activate_values.empty())
        return Error{ErrorCode::invalid_argument, "'activate_register' is set but 'activate_values' is empty"};
    if (c.activate_register < 0 && !c.deactivate_values.empty())
        return Error{ErrorCode::invalid_argument, "'deactivate_values' is set but 'activate_register' is not: "
                                                  "give the register they are written to"};

    c.state_input_registers = p.get_string("state_table") == "input";
    c.moving_mask = static_cast<std::uint32_t>(p.get_int("moving_mask"));
    c.moving_value = static_cast<std::uint32_t>(p.get_int("moving_value"));
    c.ready_mask = static_cast<std::uint32_t>(p.get_int("ready_mask"));
    c.ready_value = static_cast<std::uint32_t>(p.get_int("ready_value"));
    c.fault_mask = static_cast<std::uint32_t>(p.get_int("fault_mask"));
    if ((c.moving_mask || c.ready_mask) && !c.status.mapped())
        return Error{ErrorCode::invalid_argument, "'moving_mask'/'ready_mask' need a 'status_register'"};
    if (c.state_count() > 125)
        return Error{ErrorCode::invalid_argument,
                     "the state registers span " + std::to_string(c.state_count()) +
                         " registers; one Modbus read carries at most 125: map them closer together"};
    return c;
}

}  // namespace rollsense::modbus
