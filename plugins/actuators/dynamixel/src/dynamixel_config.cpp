#include "dynamixel_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <tuple>

namespace rollsense::dynamixel {
namespace {

Result<ControlMode> parse_mode(const std::string& s) {
    if (s == "position") return ControlMode::position;
    if (s == "extended_position") return ControlMode::extended_position;
    if (s == "current") return ControlMode::current;
    if (s == "current_based_position") return ControlMode::current_based_position;
    if (s == "velocity") return ControlMode::velocity;
    return Error{ErrorCode::invalid_argument, "unknown mode '" + s +
                                                  "' (position, extended_position, current, "
                                                  "current_based_position or velocity)"};
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

struct Refusal {
    const char* key;
    std::string message;
};

// Position mode (3) reaches one turn, ticks 0..4095: the range of the servo's
// Min/Max Position Limit items, and it ignores a goal outside them. Extended and
// current-based position modes are multi-turn (+-256 turns) and have no limits.
std::optional<Refusal> beyond_one_turn(const JointMap& j) {
    if (j.default_mode != ControlMode::position) return std::nullopt;
    const double lo = std::min(j.ticks_to_joint(0), j.ticks_to_joint(hal::dxl::kTicksPerRevolution - 1));
    const double hi = std::max(j.ticks_to_joint(0), j.ticks_to_joint(hal::dxl::kTicksPerRevolution - 1));
    for (auto [key, value] : {std::pair{"min", j.min}, std::pair{"max", j.max}}) {
        const std::int32_t tick = j.joint_to_ticks(value);
        if (tick >= 0 && tick < hal::dxl::kTicksPerRevolution) continue;
        return Refusal{key, number(value) + " " + j.unit + " is servo tick " + std::to_string(tick) +
                                ", beyond the one turn a servo reaches in position mode (ticks 0..4095: " + number(lo) +
                                " .. " + number(hi) + " " + j.unit +
                                " with this offset); the servo would refuse the goal. Keep 'min'/'max' within that "
                                "(or move 'offsets'), or give the joint modes = 'extended_position' (multi-turn)"};
    }
    return std::nullopt;
}

}  // namespace

ParamSchema dynamixel_schema() {
    ParamSchema schema{
        param_string("device", std::string("/dev/ttyUSB0"),
                     "serial port of the bus (a pty path for rollsense-dxl-emu), or 'emulator': servos emulated "
                     "in-process on an in-memory line, moving on the run clock"),
        param_number("emulated_object", etroll::kDefaultEmulatedObjectWidth,
                     "device 'emulator' only: width of an object clamped between sensing_finger and "
                     "pushing_finger (0: none); the palm fits it using finger_offset_sum and array_distance",
                     0, {}, "mm"),
        param_int("baud", 57600, "bus baud rate; must match every servo's Baud Rate item", 9600, 4500000, "bit/s"),
        param_int_list("ids", std::nullopt, "servo id of each joint", 0, 252),
        param_string_list("names", std::nullopt, "joint name of each servo, e.g. sensing_finger"),
        param_string_list("models", std::nullopt, "servo model of each joint: XM430-W350 or XL330-M288"),
        param_string_list("units", std::vector<std::string>{}, "'deg' (revolute) or 'mm' (linear) per joint; empty = all deg"),
        param_string_list("modes", std::vector<std::string>{},
                          "default operating mode per joint; empty = position (the first mode joints() reports)"),
        param_number_list("radius", std::vector<double>{},
                          "pinion or drum radius per joint for 'mm' joints (0 for 'deg' joints)", 0, {}, "mm"),
        param_number_list("ratio", std::vector<double>{},
                          "travel multiplier per joint: 2 for the palm's double rack, 1 for the winch; empty = 1", {},
                          {}),
        param_number_list("offsets", std::vector<double>{},
                          "joint position at the servo's centre (tick 2048), per joint; empty = 0"),
        param_number_list("min", std::nullopt, "lowest joint position per joint (deg or mm)"),
        param_number_list("max", std::nullopt,
                          "highest joint position per joint (deg or mm); min and max of a position-mode joint lie "
                          "within the servo's one turn (ticks 0..4095), extended position is multi-turn"),
        param_number_list("max_current", std::vector<double>{},
                          "Current Limit per joint in mA; empty or 0 = the model's maximum", 0, {}, "mA"),
        param_number_list("max_velocity", std::vector<double>{},
                          "declared velocity limit per joint (unit/s); empty or 0 = none", 0),
        param_int("retries", 3, "extra attempts after a timeout or CRC error", 0, 10),
        param_int("timeout_ms", 30, "reply timeout per status packet", 1, 1000, "ms"),
        param_bool("write_position_limits", true,
                   "write min/max into the servos' Min/Max Position Limit (position modes only)"),
        param_bool("torque_off_on_deactivate", true,
                   "turn torque off on deactivate (false: servos keep holding, e.g. a loaded winch)"),
        param_int("bus_watchdog_ms", 500,
                  "Bus Watchdog armed on every servo at activation: a servo that hears no instruction for this "
                  "long stops by itself (the process died, the cable was pulled); 0 = off. Well above the "
                  "control period; rounded up to 20 ms steps",
                  0, 2540, "ms"),
        param_string_list("inject", std::vector<std::string>{},
                          "device \"emulator\" only: faults to inject, each 'ID:KIND:AFTER_S' (run-clock seconds; "
                          "KIND silent, hardware-error, corrupt or slow), as rollsense-dxl-emu --inject"),
    };
    // device "emulator" only: the hand the emulated object sits in.
    for (auto& spec : etroll::hand_geometry_params()) schema.push_back(std::move(spec));
    return schema;
}

Result<BusConfig> parse_config(const ParamSet& params, const std::string& where) {
    // Every refusal names the parameter as the profile spells it: WHERE.KEY: what is wrong; the way out.
    auto bad = [&](const std::string& key, const std::string& message) {
        return Error{ErrorCode::invalid_argument, where + "." + key + ": " + message};
    };
    BusConfig c;
    c.device = params.get_string("device");
    c.baud = static_cast<std::uint32_t>(params.get_int("baud"));
    if (!hal::dxl::index_from_baud(c.baud)) {  // a rate no servo can be set to: nothing would ever answer
        std::string rates;
        for (std::uint8_t i = 0; i < 8; ++i) rates += (i ? ", " : "") + std::to_string(*hal::dxl::baud_from_index(i));
        return bad("baud", std::to_string(c.baud) + " is not a Dynamixel baud rate; set the servos' own rate, one of " +
                               rates + " ('rollsense dxl scan' finds it)");
    }
    c.retries = static_cast<int>(params.get_int("retries"));
    c.timeout = std::chrono::milliseconds(params.get_int("timeout_ms"));
    c.write_position_limits = params.get_bool("write_position_limits");
    c.torque_off_on_deactivate = params.get_bool("torque_off_on_deactivate");
    c.emulated_object_mm = params.get_number("emulated_object");
    c.hand = etroll::hand_geometry_from(params);
    c.bus_watchdog_ms = static_cast<int>(params.get_int("bus_watchdog_ms"));
    for (const auto& spec : params.get_string_list("inject")) {
        auto f = hal::dxl::parse_injected_fault(spec);
        if (!f.ok()) return bad("inject", f.error().message);
        c.inject.push_back(*f);
    }
    if (!c.inject.empty() && c.device != "emulator")
        return bad("inject", "needs device = \"emulator\" (the in-process emulator); for rollsense-dxl-emu "
                             "give it --inject instead, a real bus cannot be told to fail");

    const auto ids = params.get_int_list("ids");
    const auto names = params.get_string_list("names");
    const auto models = params.get_string_list("models");
    const auto units = params.get_string_list("units");
    const auto modes = params.get_string_list("modes");
    const auto radius = params.get_number_list("radius");
    const auto ratio = params.get_number_list("ratio");
    const auto offsets = params.get_number_list("offsets");
    const auto mins = params.get_number_list("min");
    const auto maxs = params.get_number_list("max");
    const auto currents = params.get_number_list("max_current");
    const auto velocities = params.get_number_list("max_velocity");
    const std::size_t n = ids.size();
    if (n == 0) return bad("ids", "is empty: list the servo id of every joint");

    for (auto [key, len, optional] :
         {std::tuple{"names", names.size(), false}, std::tuple{"models", models.size(), false},
          std::tuple{"units", units.size(), true}, std::tuple{"modes", modes.size(), true},
          std::tuple{"radius", radius.size(), true}, std::tuple{"ratio", ratio.size(), true},
          std::tuple{"offsets", offsets.size(), true}, std::tuple{"min", mins.size(), false},
          std::tuple{"max", maxs.size(), false}, std::tuple{"max_current", currents.size(), true},
          std::tuple{"max_velocity", velocities.size(), true}})
        if (len != n && !(optional && len == 0))
            return bad(key, "has " + std::to_string(len) + " entries but 'ids' has " + std::to_string(n) +
                                " (the lists are parallel: one entry per joint" +
                                (optional ? ", or none for the default)" : ")"));

    std::set<std::int64_t> seen_ids;
    std::set<std::string> seen_names;
    for (std::size_t i = 0; i < n; ++i) {
        JointMap j;
        j.name = names[i];
        const std::string joint = "joint '" + j.name + "' (id " + std::to_string(ids[i]) + "): ";
        if (j.name.empty()) return bad("names", "entry " + std::to_string(i + 1) + " is empty: name every joint");
        if (!seen_names.insert(j.name).second)
            return bad("names", "'" + j.name + "' appears twice: every joint needs its own name");
        if (!seen_ids.insert(ids[i]).second)
            return bad("ids", joint + "id " + std::to_string(ids[i]) +
                                  " appears twice: every joint is its own servo ('rollsense dxl scan' lists the bus)");
        j.id = static_cast<std::uint8_t>(ids[i]);
        j.model = hal::dxl::find_model(models[i]);
        if (!j.model) return bad("models", joint + "unknown model '" + models[i] + "' (known: XM430-W350, XL330-M288)");
        j.unit = units.empty() ? "deg" : units[i];
        if (j.unit != "deg" && j.unit != "mm") return bad("units", joint + "'" + j.unit + "' must be 'deg' or 'mm'");
        j.radius_mm = radius.empty() ? 0.0 : radius[i];
        j.ratio = ratio.empty() ? 1.0 : ratio[i];
        if (j.unit == "mm" && (j.radius_mm <= 0.0 || j.ratio == 0.0))
            return bad(j.radius_mm <= 0.0 ? "radius" : "ratio",
                       joint + "a 'mm' joint needs a positive 'radius' (pinion or drum, mm) and a non-zero 'ratio'");
        j.offset = offsets.empty() ? 0.0 : offsets[i];
        j.min = mins[i];
        j.max = maxs[i];
        if (!(j.min < j.max))
            return bad("min", joint + std::to_string(j.min) + " must be below max (" + std::to_string(j.max) + ")");
        j.max_current_ma = currents.empty() ? 0.0 : currents[i];
        if (const double top = j.model->max_current_limit * j.model->current_unit_ma; j.max_current_ma > top)
            return bad("max_current", joint + std::to_string(std::lround(j.max_current_ma)) + " mA is above the " +
                                          std::string(j.model->name) + "'s Current Limit of " +
                                          std::to_string(std::lround(top)) + " mA; give at most that, or 0 for it");
        j.max_velocity = velocities.empty() ? 0.0 : velocities[i];
        if (!modes.empty()) {
            auto m = parse_mode(modes[i]);
            if (!m.ok()) return bad("modes", joint + m.error().message);
            j.default_mode = *m;
        }
        if (auto beyond = beyond_one_turn(j)) return bad(beyond->key, joint + beyond->message);
        c.joints.push_back(std::move(j));
    }
    return c;
}

}  // namespace rollsense::dynamixel
