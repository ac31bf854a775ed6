#include "runtime/robot/robot.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <utility>

namespace rollsense::runtime {

namespace {
std::string fmt(double v) { return format_number(v, 6); }
bool is_position_mode(ControlMode m) {
    return m == ControlMode::position || m == ControlMode::extended_position ||
           m == ControlMode::current_based_position;
}
// Every control period copies every joint's state: its fault text only when it changed.
struct StateFields { double p, v, c; bool m, t; ControlMode mode; std::uint32_t bits; std::string fault; };
static_assert(sizeof(JointState) == sizeof(StateFields), "JointState changed: take_state copies it field by field");
void take_state(JointState& to, const JointState& from) {
    if (to.fault != from.fault) to.fault = from.fault;
    to.position = from.position, to.velocity = from.velocity, to.current = from.current, to.moving = from.moving;
    to.torque_enabled = from.torque_enabled, to.mode = from.mode, to.fault_bits = from.fault_bits;
}
// A joint's member, or nullptr for no joint (the JointAccess lookups).
template <class T>
const T* member_of(const Joint* j, T Joint::*member) { return j ? &(j->*member) : nullptr; }
// "a, b, c" (or "none") for messages.
template <class Range, class Name>
std::string names_of(const Range& items, Name name) {
    std::string out;
    for (const auto& x : items) out += (out.empty() ? "" : ", ") + std::string(std::invoke(name, x));
    return out.empty() ? "none" : out;
}
// One sensor hook on every sensor, in order; the first failure ends it.
template <class Slots, class Hook>
Status call_sensors(Slots& sensors, const char* verb, Hook hook) {
    for (auto& s : sensors)
        if (auto st = s.handle->call(verb, [&] { return hook(s.handle->plugin()); }); !st.ok()) return st;
    return {};
}
}  // namespace

ControlMode position_mode_of(const JointInfo& info) {
    return !info.modes.empty() && info.modes.front() == ControlMode::extended_position ? ControlMode::extended_position
                                                                                      : ControlMode::position;
}

// Where the profile writes the key of the device's params that an error names, else its params.
std::string params_site(const Profile& p, const DeviceSpec& dev, const std::string& message) {
    const std::string* key = key_named_in(message, dev.params);
    return p.site("devices." + dev.name + ".params" + (key ? "." + *key : ""));
}

JointCommand hold_command(const Joint& j) {
    JointCommand c;
    c.mode = position_mode_of(j.info);
    c.position = std::clamp(j.state.position, j.limit.min, j.limit.max);
    c.profile_velocity = j.limit.max_velocity;
    return c;
}

Result<ResolvedDevice> resolve_device(const Profile& profile, const DeviceSpec& dev, PluginRegistry& registry) {
    const std::string where = profile.at("devices." + dev.name);
    std::shared_ptr<const LoadedLibrary> lib;
    for (auto kind : {PluginKind::sensor, PluginKind::actuator, PluginKind::classifier})
        if (auto found = registry.find(dev.plugin, kind)) { lib = *found; break; }
    if (!lib)  // a sensor's search, for the full "searched" message
        return Error{ErrorCode::not_found, where + ": " + registry.find(dev.plugin, PluginKind::sensor).error().message};
    // Before its parameters (review: a classifier given params was refused for an unknown key).
    if (lib->manifest().kind == PluginKind::classifier)
        return Error{ErrorCode::invalid_argument, where + ": plugin '" + dev.plugin +
                                                      "' is a classifier; classifiers are chosen by the script, not listed as devices"};
    auto schema = PluginRegistry::schema_of(*lib);
    if (!schema) return schema.status().with_context(where);  // review: a schema() that threw named no device
    auto params = validate_params(*schema, dev.params, "devices." + dev.name + ".params");
    if (!params) return Error{params.error().code, params_site(profile, dev, params.error().message) + ": " + params.error().message};
    return ResolvedDevice{std::move(lib), std::move(*params)};
}

Result<std::unique_ptr<Robot>> Robot::create(const Profile& profile, PluginRegistry& registry,
                                             const std::filesystem::path& share_dir) {
    std::unique_ptr<Robot> r(new Robot());
    r->profile_label_ = "profile '" + profile.name + "' (" + profile.path.string() + ")";

    for (const auto& dev : profile.devices) {
        auto resolved = resolve_device(profile, dev, registry);
        if (!resolved) return resolved.error();
        const PluginContext ctx{dev.name, share_dir, profile.path, profile.virtual_clock};
        // Created and configured; a refusal names where the profile writes what the plugin refused (once).
        const auto configure = [&](auto& h) {
            auto s = h ? (*h)->configure(resolved->params, ctx)
                       : h.status().with_context(profile.at("devices." + dev.name));  // a constructor that threw
            const std::string site = s.ok() ? "" : params_site(profile, dev, s.message());
            return s.ok() || !h || s.message().find(site) != std::string::npos ? s : Status{s.code(), site + ": " + s.message()};
        };
        if (resolved->library->manifest().kind == PluginKind::sensor) {
            auto h = registry.create_sensor(dev.plugin, dev.name);
            if (auto s = configure(h); !s.ok()) return s.error();
            std::vector<ChannelInfo> channels;  // read in the handle's guard: a throw names the device (review)
            if (auto s = (*h)->call("channels", [&] { return channels = (*h)->plugin().channels(), Status{}; }); !s.ok())
                return s.error();
            r->sensors_.push_back({std::move(*h), std::move(channels), {}});
        } else {
            auto h = registry.create_actuator(dev.plugin, dev.name);
            if (auto s = configure(h); !s.ok()) return s.error();
            r->actuators_.push_back({std::move(*h), {}, {}, {}});
        }
    }

    // A trial file's column: one name each, kept whole by CSV headers and dataset-info.csv's space-separated lists.
    const auto unusable_column = [&r](const std::string& c) {
        return c.empty() || c.find_first_of(",\" \t\r\n") != std::string::npos || c == "time" || c == "valid" ||
               std::ranges::count(r->channel_columns_, c) || std::ranges::count(r->recorded_joints_, c);
    };
    // Channel columns: a lone sensor's channel names; several sensors are prefixed.
    for (auto& s : r->sensors_) {
        for (const auto& ch : s.channels) {
            const std::string column = r->sensors_.size() == 1 ? ch.name : s.handle->instance() + "_" + ch.name;
            if (unusable_column(column))
                return Error{ErrorCode::plugin_error, profile.at("devices." + s.handle->instance()) + " (plugin '" +
                                 s.handle->plugin_name() + "'): the channel column '" + column + "' is taken or "
                                 "not a column name; channel names must be unique, not 'time' or 'valid', and free of spaces, "
                                 "commas and quotes (with several sensors: <device>_<channel>)"};
            r->channel_columns_.push_back(column);
            r->channel_units_.push_back(ch.unit);
        }
        s.frame.values.assign(s.channels.size(), 0.0);
    }

    // Joint table, with profile limits required for every joint.
    for (std::size_t a = 0; a < r->actuators_.size(); ++a) {
        auto& slot = r->actuators_[a];
        auto infos = slot.handle->plugin().joints();
        for (std::size_t i = 0; i < infos.size(); ++i) {
            const auto& info = infos[i];
            for (const auto& j : r->joints_)
                if (j.name == info.name)
                    return Error{ErrorCode::invalid_argument, profile.at("devices." + slot.handle->instance()) + ": joint '" + info.name +
                                                                  "' is declared by two devices (" +
                                                                  j.actuator->instance() + " and " +
                                                                  slot.handle->instance() + ")"};
            auto lim = std::find_if(profile.joints.begin(), profile.joints.end(),
                                    [&](const JointLimit& l) { return l.name == info.name; });
            if (lim == profile.joints.end())
                return Error{ErrorCode::invalid_argument,
                             profile.at("joints") + ": joint '" + info.name + "' of device '" + slot.handle->instance() +
                                 "' has no limits; add joints." + info.name +
                                 " = { min = ..., max = ... } (the kernel enforces them; the profile's joints: " +
                                 names_of(profile.joints, &JointLimit::name) + ")"};  // a misspelt one beside the joint it meant
            // The key outside the device's range is named, so that a --set of it is said as that --set's error.
            if (!(lim->min >= info.min_position && lim->max <= info.max_position))
                return Error{ErrorCode::invalid_argument,
                             profile.at("joints." + info.name + (lim->min >= info.min_position ? ".max" : ".min")) +
                                 ": the limits [" + fmt(lim->min) + ", " + fmt(lim->max) + "] are not within what the " +
                                 "device allows [" + fmt(info.min_position) + ", " + fmt(info.max_position) + "] " +
                                 info.unit};
            Joint j{.name = info.name, .actuator = slot.handle.get(), .index = i, .info = info, .limit = *lim,
                    .command = {}, .state = {}};
            if (info.max_velocity > 0 && (j.limit.max_velocity == 0 || j.limit.max_velocity > info.max_velocity))
                j.limit.max_velocity = info.max_velocity;
            if (info.max_current > 0 && (j.limit.max_current == 0 || j.limit.max_current > info.max_current))
                j.limit.max_current = info.max_current;
            slot.joints.push_back(r->joints_.size());
            r->joints_.push_back(std::move(j));
        }
        slot.states.resize(infos.size());
        slot.commands.resize(infos.size());
    }
    for (const auto& l : profile.joints)
        if (!r->find_joint(l.name))
            return Error{ErrorCode::invalid_argument, profile.at("joints." + l.name) +
                                                          " names no joint of any device (joints: " +
                                                          r->joint_names() + ")"};
    for (const auto& name : profile.record_joints) {
        auto* j = r->find_joint(name);
        if (!j || unusable_column(name))
            return Error{ErrorCode::invalid_argument,
                         profile.at("record_joints." + std::to_string(&name - profile.record_joints.data() + 1)) + " is '" + name + "', which is " +
                             (j ? "no usable column (taken by a channel, listed twice, or with a space, comma or quote)"
                                : "not a joint (joints: " + r->joint_names() + ")")};
        r->recorded_joints_.push_back(name);
        r->recorded_joint_index_.push_back(static_cast<std::size_t>(j - r->joints_.data()));
    }
    for (const auto& j : r->joints_) r->joint_names_.push_back(j.name);
    r->joint_states_.resize(r->joints_.size());

    for (const auto& spec : profile.controllers) {
        const auto* type = find_controller_type(spec.name);
        if (!type) {
            return Error{ErrorCode::not_found, profile.at("controllers." + spec.name) + ": no such controller (known: " +
                                                   names_of(controller_type_names(), std::identity{}) + ")"};
        }
        auto params = validate_params(type->schema, spec.params, profile.at("controllers." + spec.name));
        if (!params) return params.error();
        r->controllers_.push_back({spec.name, type->create(*params), false});
    }
    return r;
}

Robot::~Robot() = default;

std::string Robot::joint_names() const { return names_of(joints_, &Joint::name); }

const Joint* Robot::find_joint(const std::string& name) const {
    for (const auto& j : joints_)
        if (j.name == name) return &j;
    return nullptr;
}
Joint* Robot::find_joint(const std::string& name) { return const_cast<Joint*>(std::as_const(*this).find_joint(name)); }

ComponentHandle* Robot::find_device(const std::string& name) {
    for (auto& a : actuators_)
        if (a.handle->instance() == name) return a.handle.get();
    for (auto& s : sensors_)
        if (s.handle->instance() == name) return s.handle.get();
    return nullptr;
}

std::string Robot::unattended_motion() const {
    for (const auto& j : joints_)
        if (j.command.torque_enabled && (j.command.mode == ControlMode::current || j.command.mode == ControlMode::velocity))
            return "joint '" + j.name + "' is driven by " + (j.command.mode == ControlMode::current ? "current" : "velocity");
    for (const auto& c : controllers_) if (c.enabled) return "controller '" + c.name + "' is on";
    return {};
}

std::vector<std::string> Robot::device_names() const {
    std::vector<std::string> out;
    for (const auto& a : actuators_) out.push_back(a.handle->instance());
    for (const auto& s : sensors_) out.push_back(s.handle->instance());
    return out;
}

Status Robot::activate(double time) {
    const auto devices = lock_devices();
    const auto start = [](ComponentHandle& h) { return h.state() == LifecycleState::inactive ? h.activate() : Status{}; };
    // Not read yet: a failure before the read below must not hold a joint at position 0 (safe_commands).
    for (auto& j : joints_) j.state.fault = "position unknown: not read since activation";
    for (auto& s : sensors_)
        if (auto st = start(*s.handle); !st.ok()) return st;
    for (auto& a : actuators_)
        if (auto st = start(*a.handle); !st.ok()) return st;
    // Latch the measured position as the command: no jump to a stale goal.
    if (auto st = read_actuators(time); !st.ok()) return st;
    for (auto& j : joints_) j.command = hold_command(j);
    return {};
}

Status Robot::read_actuators(double time) {
    for (auto& a : actuators_) {
        if (a.handle->state() != LifecycleState::active) return a.handle->require_active("read");
        auto st = a.handle->call("read", [&] { return a.handle->plugin().read(time, a.states); });
        if (!st.ok()) return st;
        for (std::size_t i = 0; i < a.joints.size(); ++i) take_state(joints_[a.joints[i]].state, a.states[i]);
    }
    return {};
}

Status Robot::write_actuators(double time) {
    for (auto& a : actuators_) {
        for (std::size_t i = 0; i < a.joints.size(); ++i) a.commands[i] = joints_[a.joints[i]].command;
        auto st = a.handle->call("write", [&] { return a.handle->plugin().write(time, a.commands); });
        if (!st.ok()) return st;
    }
    return {};
}

Status Robot::control_tick(double time, double dt) {
    const auto devices = lock_devices();
    if (auto s = read_actuators(time); !s.ok()) return s;
    // A servo keeps to its position limits in position mode only: a joint driven by current or velocity that
    // reads past a limit, or at one and going on, fails the period; the safe state holds it at that limit.
    for (const auto& j : joints_) {
        const double p = j.state.position, v = j.state.velocity, edge = std::clamp(p, j.limit.min, j.limit.max);
        if ((j.command.mode == ControlMode::current || j.command.mode == ControlMode::velocity) &&
            (p != edge || (p == j.limit.max && v > 0) || (p == j.limit.min && v < 0)))
            return {ErrorCode::limit_violation, "joint '" + j.name + "' in " + std::string(to_string(j.command.mode)) +
                                                    " mode is at " + fmt(p) + " " + j.info.unit + ", past its limit " +
                                                    fmt(edge) + " (joint limits [" + fmt(j.limit.min) + ", " + fmt(j.limit.max) +
                                                    "] of " + profile_label_ + "); stopped by the safe state (held at the limit, or torque off)"};
    }
    for (auto& c : controllers_) {
        if (!c.enabled) continue;
        if (auto s = c.controller->update(time, dt, *this); !s.ok()) {
            c.enabled = false;
            return std::move(s).with_context("controller '" + c.name + "'");
        }
    }
    return write_actuators(time);
}

void Robot::safe_commands(const ActuatorHandle& actuator, std::vector<JointCommand>& out, bool keep_released) const {
    std::size_t k = 0;  // out is sized at create(): no allocation on the way to safety
    for (const auto& j : joints_)
        if (j.actuator == &actuator && k < out.size()) {
            out[k] = hold_command(j);  // torque off: the profile says so, or the joint's fault (or unknown position)
            out[k++].torque_enabled = !j.limit.safe_torque_off && j.state.fault.empty() &&
                                      (j.command.torque_enabled || !keep_released);
        }
}

// The safe commands go to every actuator that may still drive a joint: active ones, and those in error (one silent
// servo puts its whole bus there while the others on it still push). A plugin applies what it can; its failure here
// is logged, keeps the handle's state, and a second safe_state() tries again.
void Robot::safe_state(double time, bool keep_released) noexcept {
    const auto devices = lock_devices();
    try {
        disable_all_controllers(time);
    } catch (...) {
        log_error("kernel", "safe state: a controller threw while being disabled; going on with the devices");
    }
    const auto report = [&](auto log, const std::string& text) {  // each failure once, the first 64 (robot.hpp)
        if (safe_reports_.size() < 64 && std::ranges::find(safe_reports_, text) == safe_reports_.end()) log("kernel", safe_reports_.emplace_back(text));
    };
    for (auto& a : actuators_) {
        const auto state = a.handle->state();
        if (state != LifecycleState::active && state != LifecycleState::error) continue;
        try {
            // Fresh positions where the bus still answers; the last known where it just failed (reading
            // it again would spend its timeouts first, and the write must go out within this control period).
            if (state == LifecycleState::active) {
                const auto read =
                    a.handle->call("read", [&] { return a.handle->plugin().read(time, a.states); }, true);
                if (read.ok())
                    for (std::size_t i = 0; i < a.joints.size(); ++i) joints_[a.joints[i]].state = a.states[i];
                else
                    report(log_warning, "safe state: " + read.message() + " (last known positions used)");
            }
            safe_commands(*a.handle, a.commands, keep_released);
            for (std::size_t i = 0; i < a.joints.size(); ++i) joints_[a.joints[i]].command = a.commands[i];
            auto st = a.handle->call("write", [&] { return a.handle->plugin().write(time, a.commands); }, true);
            if (!st.ok())  // its fault again: the run's error says it with its way out (review: printed thrice)
                report(log_error, "safe state: " + (st.message() == a.handle->last_error().message()
                                                        ? a.handle->describe() + ": not reached, by the same error as its fault"
                                                        : st.message()));
        } catch (...) {
            // std::bad_alloc in a message: the next device must still be tried.
            log_error("kernel", "safe state: out of memory or an exception while stopping a device");
        }
    }
}

bool Robot::shutdown(double time, bool keep_released) noexcept {
    const auto devices = lock_devices();
    safe_state(time, keep_released);
    bool clean = true;
    // Nobody else sees these statuses: logged here (a device logs no fault itself).
    // A failed device is recovered: its plugin releases what still answers (torque off), as deactivate would.
    const auto stop = [&clean](ComponentHandle& h) {
        Status s = h.state() == LifecycleState::active  ? h.deactivate()
                   : h.state() == LifecycleState::error ? h.recover()
                                                        : Status{};
        if (s.ok() && h.state() == LifecycleState::inactive) s = h.cleanup();
        if (!s.ok()) clean = false, log_error("kernel", "shutdown: " + s.message());
    };
    for (auto& a : actuators_) stop(*a.handle);
    for (auto& s : sensors_) stop(*s.handle);
    return clean;
}

void Robot::set_commands_locked(bool locked, std::string reason) { locked_ = locked, lock_reason_ = std::move(reason); }

Status Robot::command_joint(Joint& j, const JointCommand& c) {
    const std::string who = "joint '" + j.name + "'";
    if (locked_) return {ErrorCode::cancelled, who + ": command refused: " + lock_reason_};
    if (std::find(j.info.modes.begin(), j.info.modes.end(), c.mode) == j.info.modes.end())
        return {ErrorCode::invalid_argument, who + ": the device does not support " +
                                                 std::string(to_string(c.mode)) + " mode"};
    if (is_position_mode(c.mode) && (c.position < j.limit.min || c.position > j.limit.max || !std::isfinite(c.position)))
        return {ErrorCode::limit_violation, who + ": goal " + fmt(c.position) + " " + j.info.unit +
                                                " is outside the joint limits [" + fmt(j.limit.min) + ", " +
                                                fmt(j.limit.max) + "] of " + profile_label_ + "; nothing was moved"};
    // A profile velocity is a speed (0: the limit); velocity mode's goal has a sign. NaN fails every comparison.
    const double v_max = j.limit.max_velocity > 0 ? j.limit.max_velocity : DBL_MAX;
    const bool speed_ok = c.profile_velocity >= 0 && c.profile_velocity <= v_max;
    if (!speed_ok || !(std::abs(c.velocity) <= v_max))
        return {ErrorCode::limit_violation, who + ": velocity " + fmt(speed_ok ? c.velocity : c.profile_velocity) + " " +
                                                j.info.unit + "/s is outside [" + fmt(speed_ok ? -v_max : 0) + ", " +
                                                (v_max < DBL_MAX ? fmt(v_max) : "inf") + "], the velocity limits of " + profile_label_ +
                                                "; nothing was moved"};
    const bool uses_current = c.mode == ControlMode::current || c.mode == ControlMode::current_based_position;
    if (uses_current) {
        if (j.limit.max_current <= 0)
            return {ErrorCode::limit_violation,
                    who + ": no current limit is configured (joints." + j.name + ".max_current in " + profile_label_ +
                        "), so current commands are refused"};
        if (std::abs(c.current) > j.limit.max_current || !std::isfinite(c.current))
            return {ErrorCode::limit_violation,  // the device's own maximum caps the profile's (Lua review: named the profile)
                    who + ": current " + fmt(c.current) + " mA exceeds the limit " + fmt(j.limit.max_current) + " mA of " +
                        (j.limit.max_current == j.info.max_current ? "the device" : profile_label_) + "; nothing was moved"};
    }
    j.command = c;
    if (c.profile_velocity == 0 && j.limit.max_velocity > 0) j.command.profile_velocity = j.limit.max_velocity;
    return {};
}

const JointState* Robot::state(const std::string& joint) const { return member_of(find_joint(joint), &Joint::state); }
const JointInfo* Robot::info(const std::string& joint) const { return member_of(find_joint(joint), &Joint::info); }
const JointCommand* Robot::command(const std::string& joint) const { return member_of(find_joint(joint), &Joint::command); }
const JointLimit* Robot::limit(const std::string& joint) const { return member_of(find_joint(joint), &Joint::limit); }

Status Robot::set_command(const std::string& joint, const JointCommand& c) {
    auto* j = find_joint(joint);
    if (!j) return {ErrorCode::not_found, "no joint '" + joint + "' (joints: " + joint_names() + ")"};
    return command_joint(*j, c);
}

bool Robot::controller_enabled(const std::string& name) const {
    return std::any_of(controllers_.begin(), controllers_.end(), [&](const auto& c) { return c.name == name && c.enabled; });
}

Controller* Robot::find_controller(const std::string& name) {
    for (auto& c : controllers_)
        if (c.name == name) return c.controller.get();
    return nullptr;
}

Status Robot::enable_controller(const std::string& name, double time) {
    for (auto& c : controllers_) {
        if (c.name != name) continue;
        if (c.enabled) return {};
        if (locked_) return {ErrorCode::cancelled, "controller '" + name + "': refused: " + lock_reason_};
        if (auto s = c.controller->enable(time, *this); !s.ok())
            return std::move(s).with_context("controller '" + name + "'");
        c.enabled = true;
        return {};
    }
    return {ErrorCode::not_found, "no controller '" + name + "' in " + profile_label_ +
                                      " (configured: " + names_of(controllers_, &ControllerSlot::name) + ")"};
}

void Robot::disable_controller(const std::string& name, double time) {
    for (auto& c : controllers_)
        if (c.name == name && c.enabled) {
            c.controller->disable(time, *this);
            c.enabled = false;
        }
}

void Robot::disable_all_controllers(double time) {
    for (const auto& c : controllers_) disable_controller(c.name, time);
}

// The SDK hands sensors the joints as parallel name and state vectors; they are filled from the joint table when a
// sensor is called, so the table stays the one store of joint state (a copy updated on read went stale when the safe
// state re-read the joints).
SampleInput Robot::sample_input(double time) {
    for (std::size_t i = 0; i < joints_.size(); ++i) take_state(joint_states_[i], joints_[i].state);
    return SampleInput{time, &joint_names_, &joint_states_};
}

Status Robot::begin_trial(const TrialInfo& trial) {
    for (auto& s : sensors_)
        if (auto st = s.handle->require_active("begin_trial"); !st.ok()) return st;
    return call_sensors(sensors_, "begin_trial", [&](Sensor& p) { return p.begin_trial(trial); });
}

Status Robot::start_recording(double time) {
    const SampleInput in = sample_input(time);
    return call_sensors(sensors_, "start_recording", [&](Sensor& p) { return p.start_recording(in); });
}

Status Robot::stop_recording() { return call_sensors(sensors_, "stop_recording", [](Sensor& p) { return p.stop_recording(); }); }
Status Robot::end_trial() { return call_sensors(sensors_, "end_trial", [](Sensor& p) { return p.end_trial(); }); }

Status Robot::sample(double time, TrialData& data) {
    const SampleInput in = sample_input(time);
    if (data.channels.size() != channel_columns_.size()) data.channels.resize(channel_columns_.size());
    if (data.joints.size() != recorded_joints_.size()) data.joints.resize(recorded_joints_.size());
    bool valid = true;
    std::size_t column = 0;
    for (auto& s : sensors_) {
        s.frame.time = time;
        s.frame.valid = true;
        s.frame.reason.clear();
        std::fill(s.frame.values.begin(), s.frame.values.end(), 0.0);
        auto st = s.handle->call("read", [&] { return s.handle->plugin().read(in, s.frame); });
        if (!st.ok()) return st;
        if (s.frame.values.size() != s.channels.size())
            return s.handle->call("read", [&] {
                return Status(ErrorCode::plugin_error, "read() changed the frame size to " +
                                                           std::to_string(s.frame.values.size()) + " values, expected " +
                                                           std::to_string(s.channels.size()));
            });
        for (std::size_t c = 0; c < s.channels.size() && s.frame.valid; ++c)  // NaN is no reading, whatever the plugin says
            if (!std::isfinite(s.frame.values[c]))
                s.frame.valid = false, s.frame.reason = channel_columns_[column + c] + " read " + fmt(s.frame.values[c]);
        if (!s.frame.valid) {
            valid = false;
            log_debug(s.handle->instance(), "invalid sample at t=" + fmt(time) + ": " + s.frame.reason);
        }
        for (double v : s.frame.values) data.channels[column++].push_back(v);
    }
    for (std::size_t k = 0; k < recorded_joint_index_.size(); ++k)
        data.joints[k].push_back(joints_[recorded_joint_index_[k]].state.position);
    data.time.push_back(time);
    data.valid.push_back(valid ? 1 : 0);
    return {};
}

}  // namespace rollsense::runtime
