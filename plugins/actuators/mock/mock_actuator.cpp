// `mock_actuator`: a bus of modelled X-series servos, one joint each, for
// running any roll script without a hand. Parameters are parallel lists, one
// entry per joint, like a real servo bus in a profile.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mock_servo.hpp"
#include "rollsense/plugin.hpp"

namespace rollsense::mock {
namespace {

ParamSchema mock_schema() {
    return {
        param_string_list("joints", std::vector<std::string>{"sensing_finger", "pushing_finger", "palm", "winch"},
                          "joint names, one servo each"),
        param_string_list("units", std::vector<std::string>{"deg", "deg", "mm", "mm"},
                          "unit of each joint: deg (revolute) or mm (linear: palm width, winch string)"),
        param_number_list("min", std::vector<double>{-180, -180, 20, -500}, "lower travel limit of each servo"),
        param_number_list("max", std::vector<double>{180, 180, 120, 500}, "upper travel limit of each servo"),
        param_number_list("initial", std::vector<double>{0, 0, 65, 0}, "position at power-on"),
        param_number_list("max_velocity", std::vector<double>{}, "velocity limit of each servo (unit/s); empty = none", 0),
        param_number_list("max_current", std::vector<double>{}, "current limit of each servo (mA); empty = none", 0),
        param_number_list("contact", std::vector<double>{},
                          "position where each joint meets an obstacle in current mode (NaN = none); empty = none"),
        param_number("free_speed_per_ma", 0.05, "speed per mA of a current-mode joint before contact", 0, {},
                     "unit/s/mA"),
        param_string_list("extended", std::vector<std::string>{"winch"},
                          "joints driven in extended position mode (multi-turn), like the winch"),
        param_string_list("inject", std::vector<std::string>{},
                          "faults to inject, each 'JOINT:KIND:AFTER_S' (run-clock seconds); KIND silent (the joint "
                          "stops answering: its reads fail, its commands are lost) or hardware-error (overload: "
                          "torque off, reported in the joint's fault)"),
    };
}

class MockActuator final : public Actuator {
public:
    Status on_configure(const ParamSet& p, const PluginContext&) override {
        const auto names = p.get_string_list("joints");
        const auto units = p.get_string_list("units");
        const auto mins = p.get_number_list("min");
        const auto maxs = p.get_number_list("max");
        const auto init = p.get_number_list("initial");
        const auto vmax = p.get_number_list("max_velocity");
        const auto imax = p.get_number_list("max_current");
        const auto contact = p.get_number_list("contact");
        const auto extended = p.get_string_list("extended");
        const std::size_t n = names.size();
        if (n == 0) return {ErrorCode::invalid_argument, "joints is empty"};
        auto check = [&](std::size_t size, const char* key, bool optional) -> Status {
            if (size == n || (optional && size == 0)) return {};
            return {ErrorCode::invalid_argument, std::string(key) + " has " + std::to_string(size) +
                                                     " entries, joints has " + std::to_string(n)};
        };
        for (auto s : {check(units.size(), "units", false), check(mins.size(), "min", false),
                       check(maxs.size(), "max", false), check(init.size(), "initial", false),
                       check(vmax.size(), "max_velocity", true), check(imax.size(), "max_current", true),
                       check(contact.size(), "contact", true)})
            if (!s.ok()) return s;
        std::vector<JointInfo> infos;
        for (std::size_t i = 0; i < n; ++i) {
            if (units[i] != "deg" && units[i] != "mm")
                return {ErrorCode::invalid_argument, "units[" + std::to_string(i + 1) + "] is '" + units[i] +
                                                         "', expected deg or mm"};
            if (mins[i] >= maxs[i])
                return {ErrorCode::invalid_argument, "joint '" + names[i] + "': min must be below max"};
            JointInfo info;
            info.name = names[i];
            info.unit = units[i];
            info.min_position = mins[i];
            info.max_position = maxs[i];
            info.max_velocity = vmax.empty() ? 0 : vmax[i];
            info.max_current = imax.empty() ? 0 : imax[i];
            const bool ext = std::find(extended.begin(), extended.end(), names[i]) != extended.end();
            info.modes = ext ? std::vector<ControlMode>{ControlMode::extended_position, ControlMode::position,
                                                        ControlMode::current}
                             : std::vector<ControlMode>{ControlMode::position, ControlMode::current,
                                                        ControlMode::current_based_position, ControlMode::velocity};
            infos.push_back(info);
        }
        // A real servo keeps its position across a reconfiguration; so does the model.
        if (servos_.size() != n || infos_.empty() || infos_[0].name != infos[0].name) {
            servos_.clear();
            for (std::size_t i = 0; i < n; ++i) {
                ServoModel m;
                m.min_position = mins[i];
                m.max_position = maxs[i];
                m.free_speed_per_ma = p.get_number("free_speed_per_ma");
                m.contact = contact.empty() ? std::numeric_limits<double>::quiet_NaN() : contact[i];
                servos_.emplace_back(m, init[i]);
            }
        }
        std::vector<Injection> injections;
        for (const auto& spec : p.get_string_list("inject")) {
            const auto a = spec.find(':'), b = spec.rfind(':');
            const std::string where = "inject '" + spec + "'";
            if (a == std::string::npos || a == b)
                return {ErrorCode::invalid_argument, where + ": expected JOINT:KIND:AFTER_S, e.g. finger:silent:1.5"};
            Injection inj;
            const std::string joint = spec.substr(0, a), kind = spec.substr(a + 1, b - a - 1);
            const auto it = std::find(names.begin(), names.end(), joint);
            if (it == names.end()) return {ErrorCode::invalid_argument, where + ": no joint '" + joint + "'"};
            inj.joint = static_cast<std::size_t>(it - names.begin());
            if (kind != "silent" && kind != "hardware-error")
                return {ErrorCode::invalid_argument, where + ": unknown kind '" + kind +
                                                         "' (the mock knows silent and hardware-error)"};
            inj.silent = kind == "silent";
            char* end = nullptr;
            const std::string after = spec.substr(b + 1);
            inj.after = std::strtod(after.c_str(), &end);
            if (after.empty() || *end != '\0' || !std::isfinite(inj.after) || inj.after < 0)
                return {ErrorCode::invalid_argument, where + ": AFTER_S must be a number of seconds >= 0"};
            injections.push_back(inj);
        }
        injections_ = std::move(injections);
        silent_.assign(n, 0);
        silent_count_ = 0;
        infos_ = std::move(infos);
        return {};
    }

    std::vector<JointInfo> joints() const override { return infos_; }

    Status on_activate() override {
        // Hold the present position: no jump to a stale goal.
        for (auto& s : servos_) {
            JointCommand hold;
            auto st = s.state(last_time_);
            hold.mode = ControlMode::position;
            hold.position = st.position;
            s.command(last_time_, hold);
        }
        return {};
    }

    Status on_deactivate() override {
        for (auto& s : servos_) {
            JointCommand off;
            off.torque_enabled = false;
            off.position = s.state(last_time_).position;
            s.command(last_time_, off);
        }
        return {};
    }

    // A silent joint is left out: the others are read (and written) as on a
    // bus where one servo stopped answering, and the call fails naming it.
    Status read(double time, std::span<JointState> states) override {
        last_time_ = time;
        apply_injections(time);
        const std::size_t n = std::min(servos_.size(), states.size());
        for (std::size_t i = 0; i < n; ++i)
            if (!silent_[i]) servos_[i].state(time, states[i]);
        return silence();
    }

    Status write(double time, std::span<const JointCommand> commands) override {
        last_time_ = time;
        const std::size_t n = servos_.size();
        if (commands.size() != n)
            return {ErrorCode::invalid_argument, "write: " + std::to_string(commands.size()) + " commands for " +
                                                     std::to_string(n) + " joints"};
        apply_injections(time);
        for (std::size_t i = 0; i < n; ++i)
            if (!silent_[i]) servos_[i].command(time, commands[i]);
        return silence();
    }

    // set_contact {joint=, position=}; inject_fault {joint=, fault=}; clear_fault {joint=}
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override {
        auto joint_arg = [&]() -> Result<std::size_t> {
            auto it = args.find("joint");
            if (it == args.end() || !std::holds_alternative<std::string>(it->second))
                return Error{ErrorCode::invalid_argument, verb + ": needs joint = '<name>'"};
            const auto& name = std::get<std::string>(it->second);
            for (std::size_t i = 0; i < infos_.size(); ++i)
                if (infos_[i].name == name) return i;
            return Error{ErrorCode::not_found, verb + ": no joint '" + name + "'"};
        };
        if (verb == "set_contact") {
            auto j = joint_arg();
            if (!j) return j.error();
            auto it = args.find("position");
            double pos = std::numeric_limits<double>::quiet_NaN();
            if (it != args.end()) {
                if (auto* d = std::get_if<double>(&it->second)) pos = *d;
                if (auto* i = std::get_if<std::int64_t>(&it->second)) pos = static_cast<double>(*i);
            }
            servos_[*j].set_contact(pos);
            return ValueMap{};
        }
        if (verb == "inject_fault") {
            auto j = joint_arg();
            if (!j) return j.error();
            auto it = args.find("fault");
            std::string fault = it != args.end() && std::holds_alternative<std::string>(it->second)
                                    ? std::get<std::string>(it->second)
                                    : "overload";
            servos_[*j].inject_fault(last_time_, fault);
            return ValueMap{};
        }
        if (verb == "clear_fault") {
            auto j = joint_arg();
            if (!j) return j.error();
            servos_[*j].clear_fault(last_time_);
            return ValueMap{};
        }
        return Actuator::invoke(verb, args);
    }

private:
    struct Injection {
        std::size_t joint = 0;
        bool silent = false;  // false: hardware error
        double after = 0;
        bool done = false;
    };
    void apply_injections(double time) {
        for (auto& inj : injections_) {
            if (inj.done || time < inj.after) continue;
            inj.done = true;
            if (inj.silent) {
                silent_count_ += silent_[inj.joint] ? 0 : 1;
                silent_[inj.joint] = 1;
            } else {
                servos_[inj.joint].inject_fault(time, "overload (injected)");
            }
        }
    }
    Status silence() const {
        if (silent_count_ == 0) return {};  // every control period: no scan
        for (std::size_t i = 0; i < silent_.size(); ++i)
            if (silent_[i])
                return {ErrorCode::timeout, "joint '" + infos_[i].name +
                                                "' does not answer (injected fault: silent); the others were served"};
        return {};
    }

    std::vector<Injection> injections_;
    // Per joint (chars, not vector<bool>: read and write test them for every
    // joint every control period), and how many are set.
    std::vector<char> silent_;
    std::size_t silent_count_ = 0;
    std::vector<JointInfo> infos_;
    std::vector<MockServo> servos_;
    double last_time_ = 0;
};

}  // namespace
}  // namespace rollsense::mock

ROLLSENSE_PLUGIN(rollsense::mock::MockActuator, actuator, "mock_actuator", "1.0.0",
                 "Modelled X-series servos (trapezoidal profiles, current mode against a contact)",
                 rollsense::mock::mock_schema)
