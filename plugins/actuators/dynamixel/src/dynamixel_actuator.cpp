#include "dynamixel_actuator.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include "rollsense/hal/dynamixel/last_resort.hpp"
#include "rollsense/log.hpp"

namespace rollsense::dynamixel {

using namespace hal::dxl;

namespace {

constexpr const char* kLog = "dynamixel";

std::vector<ControlMode> modes_for(ControlMode first) {
    std::vector<ControlMode> out{first};
    for (auto m : {ControlMode::position, ControlMode::extended_position, ControlMode::current_based_position,
                   ControlMode::current, ControlMode::velocity})
        if (m != first) out.push_back(m);
    return out;
}

bool is_position_mode(ControlMode m) {
    return m == ControlMode::position || m == ControlMode::extended_position ||
           m == ControlMode::current_based_position;
}

// One servo's entry of the per-period SYNC_WRITE: Goal Current .. Goal Position.
Bytes command_block(std::int32_t current, std::int32_t velocity, std::int32_t profile_acceleration,
                    std::int32_t profile_velocity, std::int32_t position) {
    Bytes d;
    d.reserve(kCommandBlockLength);
    put_le(d, current, 2);               // 102 Goal Current
    put_le(d, velocity, 4);              // 104 Goal Velocity
    put_le(d, profile_acceleration, 4);  // 108 Profile Acceleration
    put_le(d, profile_velocity, 4);      // 112 Profile Velocity
    put_le(d, position, 4);              // 116 Goal Position
    return d;
}

}  // namespace

DynamixelActuator::~DynamixelActuator() { disarm_last_resort(); }

void DynamixelActuator::arm_last_resort() {
    disarm_last_resort();
    Bytes params;
    put_le(params, addr::torque_enable, 2);
    put_le(params, 1, 2);
    for (auto id : ids_) {
        params.push_back(id);
        params.push_back(0);
    }
    const Bytes packet = build_instruction(kBroadcastId, Instruction::sync_write, params);
    if (bus_->port().fd() < 0) return;  // servos emulated in memory die with the process
    last_resort_slot_ = register_last_resort(bus_->port().fd(), packet);
    if (last_resort_slot_ < 0)
        log_warning(kLog, "no crash-time torque-off for this bus (too many buses or servos); the Bus Watchdog "
                          "still stops the servos");
}

void DynamixelActuator::disarm_last_resort() {
    unregister_last_resort(last_resort_slot_);
    last_resort_slot_ = -1;
}

std::string DynamixelActuator::who(std::size_t i) const {
    return "joint '" + config_.joints[i].name + "' (servo " + std::to_string(config_.joints[i].id) + ")";
}

Status DynamixelActuator::with_joint(std::size_t i, Status st) const {
    if (st.ok()) return st;
    if (bus_ && bus_->port_failed()) return port_failure(std::move(st));
    return std::move(st).with_context(who(i));
}

Status DynamixelActuator::port_failure(Status st) const {
    if (st.ok()) return st;
    return {st.code(), st.message() + "; check the USB adapter and its cable, and that " + config_.device +
                           " still exists (a rollsense-dxl-emu link: restart the emulator)"};
}

Status DynamixelActuator::on_configure(const ParamSet& params, const PluginContext& context) {
    // Refusals name the profile's file and the parameter, as the kernel's own profile errors do.
    where_ = "devices." + (context.instance.empty() ? std::string("<device>") : context.instance) + ".params";
    if (!context.profile_path.empty()) where_ = context.profile_path.string() + ": " + where_;
    auto cfg = parse_config(params, where_);
    if (!cfg.ok()) return cfg.status();
    config_ = std::move(cfg).value();

    infos_.clear();
    ids_.clear();
    rt_.assign(config_.joints.size(), Runtime{});
    for (std::size_t i = 0; i < config_.joints.size(); ++i) {
        const auto& j = config_.joints[i];
        JointInfo info;
        info.name = j.name;
        info.unit = j.unit;
        info.min_position = j.min;
        info.max_position = j.max;
        info.max_velocity = j.max_velocity;
        info.max_current = j.current_units_to_ma(j.current_limit_units());
        info.modes = modes_for(j.default_mode);
        infos_.push_back(info);
        ids_.push_back(j.id);
        rt_[i].mode = j.default_mode;
    }

    disarm_last_resort();
    bus_.reset();
    emulator_ = nullptr;
    const BusOptions options{config_.timeout, config_.retries};
    if (config_.device == "emulator") {
        auto link = start_in_process_emulator(config_);
        if (!link.ok()) return Error{link.error().code, where_ + "." + link.error().message};
        emulator_ = link->get();
        bus_ = std::make_unique<Bus>(std::move(link).value(), options);
    } else {
        auto port = hal::SerialPort::open(config_.device, config_.baud);
        if (!port.ok()) return port.status();
        bus_ = std::make_unique<Bus>(std::move(port).value(), options);
    }
    return check_servos();
}

Status DynamixelActuator::check_servos() {
    for (std::size_t i = 0; i < config_.joints.size(); ++i) {
        const auto& j = config_.joints[i];
        auto reply = bus_->ping(j.id);
        if (!reply.ok())
            return with_joint(i, Status(reply.error().code,
                                        reply.error().message + "; is it on " + config_.device + " at " +
                                            std::to_string(config_.baud) + " baud?"));
        if (reply->model_number != j.model->model_number) {
            const auto* found = find_model(reply->model_number);
            return {ErrorCode::invalid_argument,
                    where_ + ".models: " + who(i) + ": the profile says " + std::string(j.model->name) +
                        " but the servo is " +
                        (found ? std::string(found->name) : "model " + std::to_string(reply->model_number)) +
                        "; fix 'models' or the id"};
        }
    }
    return {};
}

Status DynamixelActuator::set_torque(std::size_t i, bool on) {
    if (auto st = bus_->write_value(ids_[i], addr::torque_enable, 1, on ? 1 : 0); !st.ok()) return with_joint(i, st);
    rt_[i].torque = on;
    return {};
}

Status DynamixelActuator::set_watchdog(std::size_t i, int ms) {
    auto now = bus_->read_value(ids_[i], addr::bus_watchdog, 1);
    if (!now.ok()) return with_joint(i, now.status());
    if (*now < 0) {
        log_warning(kLog, who(i) + " had stopped by its Bus Watchdog (no instruction in time: the previous run "
                                   "was killed, or the bus stalled); cleared");
        if (auto st = bus_->write_value(ids_[i], addr::bus_watchdog, 1, 0); !st.ok()) return with_joint(i, st);
    }
    rt_[i].watchdog_tripped = false;
    watchdog_ms_ = ms;
    const int units = (ms + 19) / 20;  // round up: never shorter than asked
    if (*now == units) return {};
    return with_joint(i, bus_->write_value(ids_[i], addr::bus_watchdog, 1, units));
}

Status DynamixelActuator::watchdog_fault(std::size_t i) const {
    return {ErrorCode::hardware_fault,
            who(i) + ": its Bus Watchdog (address 98) tripped: no instruction reached it for " +
                std::to_string(watchdog_ms_) + " ms (bus_watchdog_ms; the control loop paused that long), so the "
                "servo stopped and ignores every goal until 98 is written 0. Keep control periods well under "
                "bus_watchdog_ms (device:call('rest') before long work without control); the next activation clears it"};
}

Status DynamixelActuator::prepare(std::size_t i, ControlMode mode) {
    const auto& j = config_.joints[i];
    const std::uint8_t id = ids_[i];
    // Torque Enable (64) is right after the EEPROM block; read 11..64 in one go.
    auto block = bus_->read(id, addr::operating_mode, addr::torque_enable - addr::operating_mode + 1);
    if (!block.ok()) return with_joint(i, block.status());
    auto item = [&](std::uint16_t a, std::uint16_t size) {
        return get_le_signed(&block->data[a - addr::operating_mode], size);
    };
    rt_[i].torque = item(addr::torque_enable, 1) != 0;

    struct Change {
        std::uint16_t address, size;
        std::int64_t value;
    };
    std::vector<Change> changes;
    const auto op = static_cast<std::int64_t>(to_operating_mode(mode));
    if (item(addr::operating_mode, 1) != op) changes.push_back({addr::operating_mode, 1, op});
    const auto limit = j.current_limit_units();
    if (item(addr::current_limit, 2) != limit) changes.push_back({addr::current_limit, 2, limit});
    if (config_.write_position_limits && mode == ControlMode::position) {
        const auto [lo, hi] = tick_range(j);
        if (lo >= 0 && hi <= 4095) {
            if (item(addr::max_position_limit, 4) != hi) changes.push_back({addr::max_position_limit, 4, hi});
            if (item(addr::min_position_limit, 4) != lo) changes.push_back({addr::min_position_limit, 4, lo});
        } else {  // a multi-turn joint switched to position mode (a position-mode one was refused at configure)
            log_warning(kLog, who(i) + ": limits [" + std::to_string(j.min) + ", " + std::to_string(j.max) +
                                  "] fall outside one turn (ticks " + std::to_string(lo) + ".." + std::to_string(hi) +
                                  "); servo position limits left unchanged");
        }
    }
    if (!changes.empty() && rt_[i].torque) {
        // EEPROM is writable only with torque off.
        if (auto st = set_torque(i, false); !st.ok()) return st;
    }
    for (const auto& c : changes)
        if (auto st = bus_->write_value(id, c.address, c.size, c.value); !st.ok()) return with_joint(i, st);
    rt_[i].mode = mode;
    rt_[i].velocity_limit = item(addr::velocity_limit, 4);
    rt_[i].min_ticks = item(addr::min_position_limit, 4);
    rt_[i].max_ticks = item(addr::max_position_limit, 4);
    for (const auto& c : changes) {
        if (c.address == addr::min_position_limit) rt_[i].min_ticks = static_cast<std::int32_t>(c.value);
        if (c.address == addr::max_position_limit) rt_[i].max_ticks = static_cast<std::int32_t>(c.value);
    }
    return {};
}

std::pair<std::int32_t, std::int32_t> DynamixelActuator::tick_range(const JointMap& j) {
    const auto a = j.joint_to_ticks(j.min), b = j.joint_to_ticks(j.max);
    return {std::min(a, b), std::max(a, b)};
}

std::pair<std::int32_t, std::int32_t> DynamixelActuator::position_limits_after_switch(std::size_t i) const {
    if (rt_[i].mode == ControlMode::position) return {rt_[i].min_ticks, rt_[i].max_ticks};
    // prepare() writes the joint's own range when it fits one turn and it may; else the stored ones stay, within it.
    if (const auto [lo, hi] = tick_range(config_.joints[i]); config_.write_position_limits && lo >= 0 && hi <= 4095)
        return {lo, hi};
    return {std::max(rt_[i].min_ticks, 0), std::min(rt_[i].max_ticks, 4095)};
}

Status DynamixelActuator::hold_here(std::size_t i) {
    const std::uint8_t id = ids_[i];
    auto present = bus_->read_value(id, addr::present_position, 4);
    if (!present.ok()) return with_joint(i, present.status());
    rt_[i].present_ticks = *present;
    // The goal becomes where the servo is, before torque comes on: no jump to
    // whatever Goal Position was left from a previous run.
    if (is_position_mode(rt_[i].mode)) {
        if (auto st = bus_->write_value(id, addr::goal_position, 4, *present); !st.ok()) {
            if (st.code() == ErrorCode::limit_violation) {
                const auto& j = config_.joints[i];
                return {ErrorCode::hardware_fault,
                        who(i) + " is at " + std::to_string(j.ticks_to_joint(*present)) + " " + j.unit +
                            ", outside its limits [" + std::to_string(j.min) + ", " + std::to_string(j.max) +
                            "]; move it inside by hand (torque is off) or widen 'min'/'max'"};
            }
            return with_joint(i, st);
        }
    } else if (rt_[i].mode == ControlMode::current) {
        if (auto st = bus_->write_value(id, addr::goal_current, 2, 0); !st.ok()) return with_joint(i, st);
    } else if (rt_[i].mode == ControlMode::velocity) {
        if (auto st = bus_->write_value(id, addr::goal_velocity, 4, 0); !st.ok()) return with_joint(i, st);
    }
    return set_torque(i, true);
}

Status DynamixelActuator::activate_servo(std::size_t i) {
    auto hw = bus_->read_value(ids_[i], addr::hardware_error_status, 1);
    if (!hw.ok()) return with_joint(i, hw.status());
    rt_[i].hardware_error = static_cast<std::uint8_t>(*hw);
    // Said once, by this refusal: the safe state's release that follows does not warn of it again.
    rt_[i].hardware_error_told = *hw != 0;
    if (*hw != 0)
        return {ErrorCode::hardware_fault,
                who(i) + " reports a hardware error: " + describe_hardware_error(rt_[i].hardware_error) +
                    "; remove the cause, then " + reboot_way_out(i, false)};
    // Cleared before the goals are written: a tripped watchdog makes them read-only.
    if (auto st = set_watchdog(i, 0); !st.ok()) return st;
    if (auto st = prepare(i, config_.joints[i].default_mode); !st.ok()) return st;
    if (auto st = hold_here(i); !st.ok()) return st;
    return set_watchdog(i, config_.bus_watchdog_ms);
}

Status DynamixelActuator::on_activate() {
    if (!bus_) return {ErrorCode::state_error, "the bus is not open (configure first)"};
    last_io_time_ = std::nan("");  // the kernel reads right after activation: no pause to look for
    for (std::size_t i = 0; i < ids_.size(); ++i) {
        if (auto st = activate_servo(i); !st.ok()) {
            // A refused activation leaves nothing holding: every servo that
            // answers gets torque off (those already switched on included),
            // whatever torque_off_on_deactivate says: the run never started.
            (void)release_servos();
            return st;
        }
    }
    arm_last_resort();
    return {};
}

DynamixelActuator::Release DynamixelActuator::release_servos() {
    Release out;
    auto& unconfirmed = out.servos;
    std::vector<SyncWriteEntry> off;
    for (std::size_t i = 0; i < ids_.size(); ++i) {
        // Written, not read first: a servo whose replies are corrupt still carries out a WRITE.
        Status st;
        if (config_.bus_watchdog_ms > 0)  // no trip while the bus is idle
            st = with_joint(i, bus_->write_value(ids_[i], addr::bus_watchdog, 1, 0));
        if (auto torque = set_torque(i, false); st.ok()) st = std::move(torque);  // keep going: every servo we can
        if (st.ok()) continue;
        unconfirmed.push_back({i, std::move(st)});
        off.push_back({ids_[i], Bytes{0}});
    }
    // Once more for those that did not confirm, as a SYNC_WRITE: it asks for no
    // reply, so a servo that hears but cannot answer cleanly is released too.
    if (!off.empty()) {
        if (config_.bus_watchdog_ms > 0) out.resend = bus_->sync_write(addr::bus_watchdog, 1, off);
        if (auto st = bus_->sync_write(addr::torque_enable, 1, off); out.resend.ok()) out.resend = std::move(st);
    }
    return out;
}

Status DynamixelActuator::not_confirmed(const Release& release, bool with_reasons) const {
    const auto& servos = release.servos;
    if (servos.empty()) return {};
    // A dead port: every servo's error is the same port error, said once, by the resend's; after the device's fault
    // (!with_reasons), whose error is the run's, with its way out, the port's error alone (user review: the emulator
    // killed mid-run printed the port's error and way out three times).
    const bool port_dead = !release.resend.ok();
    std::string list;
    for (const auto& [i, why] : servos)
        list += (list.empty() ? "" : "; ") +
                (port_dead ? who(i)
                           : with_reasons ? why.error().describe()  // it names the joint
                                          : who(i) + " (" + std::string(to_string(why.code())) + ")");
    const std::string check = "check the torque is off (rollsense dxl info) before the next run";
    // Review: "Both were sent once more" was said when the port was gone and nothing could be sent.
    const std::string resend =
        !port_dead     ? ". Both were sent once more without asking for a reply (SYNC_WRITE); " + check
        : with_reasons ? ". Sending both once more without asking for a reply (SYNC_WRITE) failed too: " +
                             port_failure(release.resend).message() + "; then " + check
                       : ". Sending both once more without asking for a reply (SYNC_WRITE) failed too, the port being "
                         "gone (" + release.resend.message() + "); once it is back, " + check;
    return {servos.front().second.code(), "not confirmed released (torque off, Bus Watchdog 0): " + list + resend};
}

Status DynamixelActuator::on_deactivate() {
    rearm_watchdog_ = false;
    if (!bus_ || !config_.torque_off_on_deactivate) return {};
    return not_confirmed(release_servos(), true);
}

Status DynamixelActuator::on_cleanup() {
    disarm_last_resort();
    bus_.reset();
    emulator_ = nullptr;
    return {};
}

// After a fault the kernel's shutdown recovers the device (the error state
// has no deactivate): the servos that still answer are released as a
// deactivate would, before the bus closes; the silent one costs its timeouts.
Status DynamixelActuator::on_recover() {
    disarm_last_resort();
    // The fault that brought the device here was reported: only who is not known to be released.
    if (bus_ && config_.torque_off_on_deactivate)
        if (auto st = not_confirmed(release_servos(), false); !st.ok()) log_warning(kLog, st.message());
    bus_.reset();
    emulator_ = nullptr;
    rt_.assign(config_.joints.size(), Runtime{});
    return {};
}

Status DynamixelActuator::read(double time, std::span<JointState> states) {
    if (!bus_) return {ErrorCode::state_error, "the bus is not open (configure first)"};
    // Every packet written so far is already in effect (the line hands bytes
    // over synchronously): the servos move under the goals last written.
    if (emulator_) emulator_->advance_servos_to(time);
    if (states.size() != ids_.size())
        return {ErrorCode::invalid_argument, "read() got " + std::to_string(states.size()) + " states for " +
                                                 std::to_string(ids_.size()) + " joints"};
    auto replies = bus_->sync_read(ids_, kStateBlockAddress, kStateBlockLength);
    if (!replies.ok()) {  // named by joint, as every other fault of one servo is
        const auto failed = std::find(ids_.begin(), ids_.end(), bus_->last_failed_id().value_or(0));
        return failed == ids_.end() ? (bus_->port_failed() ? port_failure(replies.status()) : replies.status())
                                    : with_joint(static_cast<std::size_t>(failed - ids_.begin()), replies.status());
    }
    for (std::size_t i = 0; i < ids_.size(); ++i) {
        const auto& j = config_.joints[i];
        const auto& r = (*replies)[i];
        const std::uint8_t* d = r.data.data();
        auto at = [&](std::uint16_t a) { return d + (a - kStateBlockAddress); };
        auto& s = states[i];
        rt_[i].present_ticks = get_le_signed(at(addr::present_position), 4);
        s.position = j.ticks_to_joint(rt_[i].present_ticks);
        s.velocity = j.velocity_units_to_joint(get_le_signed(at(addr::present_velocity), 4));
        s.current = j.current_units_to_ma(get_le_signed(at(addr::present_current), 2));
        s.moving = *at(addr::moving) != 0;
        s.mode = rt_[i].mode;
        if (r.alert) {
            // Only now is the extra READ worth its bus time.
            auto hw = bus_->read_value(ids_[i], addr::hardware_error_status, 1);
            if (!hw.ok()) return with_joint(i, hw.status());
            const auto bits = static_cast<std::uint8_t>(*hw);
            if (bits != rt_[i].hardware_error) rt_[i].hardware_error_told = false;  // said once, by write()
            rt_[i].hardware_error = bits;
            rt_[i].torque = false;  // the firmware turned it off
        } else {
            rt_[i].hardware_error = 0;
        }
        s.torque_enabled = rt_[i].torque;
        s.fault_bits = rt_[i].hardware_error;
        s.fault = rt_[i].hardware_error ? describe_hardware_error(rt_[i].hardware_error) : std::string();
    }
    // A SYNC_WRITE has no reply: a tripped Bus Watchdog would drop every goal
    // unseen. It trips only after a pause in our instructions, so 98 is read
    // only after a pause of half its time (two clocks), never in a steady run.
    // Every servo is looked at, not up to the first that tripped: write() must know each one whose goals are
    // read-only, or a mode switch would switch torque back on towards a goal left from before the pause (review: a
    // finger swept 138 degrees after a stall).
    const bool paused = watchdog_ms_ > 0 && time - last_io_time_ > watchdog_ms_ * 0.5e-3;
    last_io_time_ = time;
    Status first;
    for (std::size_t i = 0; i < ids_.size(); ++i) {
        if (paused && rt_[i].torque && !rt_[i].watchdog_tripped) {
            auto wd = bus_->read_value(ids_[i], addr::bus_watchdog, 1);
            if (!wd.ok()) {
                if (first.ok()) first = with_joint(i, wd.status());
                continue;
            }
            rt_[i].watchdog_tripped = *wd < 0;
        }
        if (rt_[i].watchdog_tripped && first.ok()) first = watchdog_fault(i);
    }
    return first;
}

// Two phases. First every command is checked (a refused command moves
// nothing at all). Then the bus work, servo by servo: a servo that fails to
// answer (silent, corrupt replies, a hardware error) is left out and the
// others still get their commands, so the safe state reaches every servo that
// still answers; the first failure is returned, naming its joint.
Status DynamixelActuator::write(double time, std::span<const JointCommand> commands) {
    if (!bus_) return {ErrorCode::state_error, "the bus is not open (configure first)"};
    if (commands.size() != ids_.size())
        return {ErrorCode::invalid_argument, "write() got " + std::to_string(commands.size()) + " commands for " +
                                                 std::to_string(ids_.size()) + " joints"};
    std::vector<std::int32_t> goal_ticks(ids_.size());
    for (std::size_t i = 0; i < ids_.size(); ++i) {
        const auto& j = config_.joints[i];
        const auto& c = commands[i];
        // A joint under control: the run's error. A released one: a warning, once (review: it was logged when read,
        // then printed again as the run's error).
        if (rt_[i].hardware_error && !c.torque_enabled && !rt_[i].hardware_error_told)
            log_warning(kLog, who(i) + ": hardware error (" + describe_hardware_error(rt_[i].hardware_error) +
                                  ") while released; the servo turned its torque off. Before it moves again, "
                                  "remove the cause, then " + reboot_way_out(i, true));
        rt_[i].hardware_error_told = rt_[i].hardware_error != 0;
        if (rt_[i].hardware_error && c.torque_enabled)
            return {ErrorCode::hardware_fault,
                    who(i) + ": hardware error (" + describe_hardware_error(rt_[i].hardware_error) +
                        "); the servo turned its torque off. Remove the cause, then " + reboot_way_out(i, true)};
        if (!c.torque_enabled) continue;  // a release: no goal is sent (below), nothing to check
        if (is_position_mode(c.mode) && (c.position < j.min - 1e-9 || c.position > j.max + 1e-9))
            return {ErrorCode::limit_violation, who(i) + ": goal " + std::to_string(c.position) + " " + j.unit +
                                                    " is outside [" + std::to_string(j.min) + ", " +
                                                    std::to_string(j.max) + "]"};
        goal_ticks[i] = is_position_mode(c.mode) ? j.joint_to_ticks(c.position) : rt_[i].present_ticks;
        // The servo would silently drop a SYNC_WRITE entry outside its position limits; after a switch to position
        // mode, the limits it will have: refused here, before the switch turns torque off (review: the winch let go).
        if (const auto [lo, hi] = position_limits_after_switch(i);
            c.mode == ControlMode::position && (goal_ticks[i] < lo || goal_ticks[i] > hi))
            return {ErrorCode::limit_violation,
                    who(i) + ": goal " + std::to_string(c.position) + " " + j.unit + " is tick " +
                        std::to_string(goal_ticks[i]) + ", outside the servo's position limits " + std::to_string(lo) +
                        ".." + std::to_string(hi) + " in position mode (check 'rollsense dxl info', let the plugin "
                        "write them: write_position_limits = true, or use extended_position mode beyond one turn)"};
    }

    last_io_time_ = time;
    Status first;
    auto failed = [&](Status st) {
        if (first.ok()) first = std::move(st);
    };
    std::vector<SyncWriteEntry> entries;
    std::vector<std::size_t> enable_after;
    for (std::size_t i = 0; i < ids_.size(); ++i) {
        const auto& j = config_.joints[i];
        const auto& c = commands[i];
        // A release: torque off, goal and mode left as they are (the safe state
        // releases joints whose position it never read: their goal must not become 0).
        if (!c.torque_enabled) {
            if (rt_[i].torque)
                if (auto st = set_torque(i, false); !st.ok()) failed(std::move(st));
            continue;
        }
        if (rt_[i].watchdog_tripped) {  // its goals are read-only: the others still get theirs
            // Short: the read that found the trip said why and what to do (the safe state logs this one).
            failed({ErrorCode::hardware_fault, who(i) + ": its Bus Watchdog (address 98) tripped: goal not sent "
                                                        "(the servo stopped by itself and ignores goals)"});
            continue;
        }
        if (c.mode != rt_[i].mode) {
            // Operating Mode is EEPROM: torque off, switch, and torque comes
            // back only after this period's goals are in place.
            if (auto st = prepare(i, c.mode); !st.ok()) {
                failed(std::move(st));
                // A servo that cannot answer may still hear: one pushing or
                // spinning gets Goal Current / Goal Velocity 0 in the SYNC_WRITE,
                // which asks for no reply (the mode switch, the safe hold, needs them).
                if (rt_[i].mode == ControlMode::current || rt_[i].mode == ControlMode::velocity)
                    entries.push_back({ids_[i], command_block(0, 0, 0, 0, rt_[i].present_ticks)});
                continue;
            }
            if (rt_[i].torque)
                if (auto st = set_torque(i, false); !st.ok()) {
                    failed(std::move(st));
                    continue;
                }
            log_debug(kLog, who(i) + ": now in " + std::string(to_string(c.mode)) + " mode");
            if (c.mode == ControlMode::position &&
                (goal_ticks[i] < rt_[i].min_ticks || goal_ticks[i] > rt_[i].max_ticks)) {
                failed({ErrorCode::limit_violation, who(i) + ": goal tick " + std::to_string(goal_ticks[i]) +
                                                        " is outside the servo's position limits " +
                                                        std::to_string(rt_[i].min_ticks) + ".." +
                                                        std::to_string(rt_[i].max_ticks)});
                continue;
            }
        }
        if (!rt_[i].torque) enable_after.push_back(i);

        const std::int32_t limit = j.current_limit_units();
        std::int32_t goal_current = limit;
        if (c.mode == ControlMode::current) goal_current = std::clamp(j.ma_to_current_units(c.current), -limit, limit);
        if (c.mode == ControlMode::current_based_position)
            goal_current = std::clamp(std::abs(j.ma_to_current_units(c.current)), 0, limit);
        std::int32_t goal_velocity = 0;
        if (c.mode == ControlMode::velocity)
            goal_velocity = std::clamp(j.joint_to_velocity_units(c.velocity), -rt_[i].velocity_limit,
                                       rt_[i].velocity_limit);

        entries.push_back({ids_[i], command_block(goal_current, goal_velocity,
                                                  j.joint_to_profile_acceleration(c.profile_acceleration),
                                                  j.joint_to_profile_velocity(c.profile_velocity), goal_ticks[i])});
    }
    if (!entries.empty())
        if (auto st = bus_->sync_write(kCommandBlockAddress, kCommandBlockLength, entries); !st.ok())
            return bus_->port_failed() ? port_failure(std::move(st)) : st;
    for (auto i : enable_after)
        if (auto st = set_torque(i, true); !st.ok()) failed(std::move(st));
    // Control has resumed after a rest (invoke "rest"): the goals are out, now
    // the servos guard themselves again.
    if (rearm_watchdog_ && first.ok()) {
        for (std::size_t i = 0; i < ids_.size() && first.ok(); ++i)
            if (auto st = set_watchdog(i, config_.bus_watchdog_ms); !st.ok()) failed(std::move(st));
        rearm_watchdog_ = !first.ok();
        if (!rearm_watchdog_) log_debug(kLog, "Bus Watchdog re-armed: control has resumed");
    }
    return first;
}

Result<std::size_t> DynamixelActuator::joint_index(const ValueMap& args) const {
    auto it = args.find("joint");
    if (it == args.end() || !std::holds_alternative<std::string>(it->second))
        return Error{ErrorCode::invalid_argument, "needs {joint = '<name>'}"};
    const auto& name = std::get<std::string>(it->second);
    for (std::size_t i = 0; i < config_.joints.size(); ++i)
        if (config_.joints[i].name == name) return i;
    std::string known;
    for (const auto& j : config_.joints) known += (known.empty() ? "" : ", ") + j.name;
    return Error{ErrorCode::not_found, "no joint '" + name + "' on this bus (joints: " + known + ")"};
}

std::string DynamixelActuator::reboot_way_out(std::size_t i, bool in_script) const {
    const std::string call = "device:call('reboot', {joint='" + config_.joints[i].name + "'})";
    if (config_.device == "emulator")  // no port outside this process: the next run's emulated servos start afresh
        return in_script ? "reboot it from a cleanup function (rs.on_cleanup): " + call +
                               ", or run again (the emulated servos start afresh)"
                         : "run again (the emulated servos start afresh)";
    // The port as one shell word (a path with a space in it would not paste).
    const bool plain = std::all_of(config_.device.begin(), config_.device.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("/._-:+").find(c) != std::string_view::npos;
    });
    const std::string port = plain ? config_.device : "'" + config_.device + "'";
    const std::string command = "rollsense dxl reboot --device " + port + " --baud " + std::to_string(config_.baud) +
                                " --id " + std::to_string(ids_[i]);
    // While the run holds the port the command is refused (its lock), and a device's fault ends the script: its cleanup
    // functions may reboot it (hardware review: "a script that carries on" was no way out, none can).
    if (in_script) return "reboot it: a cleanup function (rs.on_cleanup) can call " + call + "; after the run: " + command +
                          " (or power-cycle it)";
    return "reboot it: " + command + " (or power-cycle it)";
}

Status DynamixelActuator::reboot_joint(std::size_t i) {
    if (auto st = bus_->reboot(ids_[i]); !st.ok()) return with_joint(i, st);
    // The servo restarts after answering; it is back within about half a second
    // (waited on the line's clock: no wall time on the in-memory emulator).
    Status last;
    for (int attempt = 0; attempt < 20; ++attempt) {
        bus_->port().pause(std::chrono::milliseconds(50));
        auto p = bus_->ping(ids_[i]);
        if (p.ok()) {
            last = {};
            break;
        }
        last = p.status();
    }
    if (!last.ok()) return with_joint(i, Status(last.code(), "did not come back after REBOOT: " + last.message()));
    rt_[i].hardware_error = 0;
    rt_[i].torque = false;
    const ControlMode mode = rt_[i].mode;
    if (auto st = prepare(i, mode); !st.ok()) return st;
    if (auto st = hold_here(i); !st.ok()) return st;
    return set_watchdog(i, config_.bus_watchdog_ms);  // RAM: lost in the reboot
}

Result<ValueMap> DynamixelActuator::invoke(const std::string& verb, const ValueMap& args) {
    if (verb == "reboot") {
        if (!bus_) return Error{ErrorCode::state_error, "reboot: the bus is not open (configure first)"};
        auto i = joint_index(args);
        if (!i.ok()) return Error{i.error().code, "reboot: " + i.error().message};
        if (auto st = reboot_joint(*i); !st.ok()) return st;
        return ValueMap{{"joint", config_.joints[*i].name}, {"rebooted", true}};
    }
    if (verb == "rest") {
        // Before long work on the script thread (rs.analyse), when no control
        // period runs: every servo's Bus Watchdog off, so a healthy run never
        // trips it, and back to bus_watchdog_ms by the first write after, when
        // control resumes (a script that rolls again is guarded again).
        if (!bus_) return Error{ErrorCode::state_error, "rest: the bus is not open (configure first)"};
        for (std::size_t i = 0; i < ids_.size(); ++i)
            if (auto st = set_watchdog(i, 0); !st.ok()) return st;
        rearm_watchdog_ = config_.bus_watchdog_ms > 0;
        return ValueMap{{"rearm_ms", static_cast<std::int64_t>(config_.bus_watchdog_ms)}};
    }
    if (verb == "watchdog" && args.empty()) {
        // {}: read every servo's Bus Watchdog back (address 98), in ms; -1 = tripped.
        if (!bus_) return Error{ErrorCode::state_error, "watchdog: the bus is not open (configure first)"};
        ValueMap out;
        for (std::size_t i = 0; i < ids_.size(); ++i) {
            auto now = bus_->read_value(ids_[i], addr::bus_watchdog, 1);
            if (!now.ok()) return with_joint(i, now.status());
            out[config_.joints[i].name] = static_cast<std::int64_t>(*now < 0 ? -1 : *now * 20);
        }
        return out;
    }
    if (verb == "watchdog") {
        // {ms = N}: every servo's Bus Watchdog (0 = off), until changed again.
        if (!bus_) return Error{ErrorCode::state_error, "watchdog: the bus is not open (configure first)"};
        rearm_watchdog_ = false;
        auto it = args.find("ms");
        const auto* ms = it == args.end() ? nullptr : std::get_if<std::int64_t>(&it->second);
        if (!ms || *ms < 0 || *ms > 2540)
            return Error{ErrorCode::invalid_argument, "watchdog: needs {ms = 0..2540} (0 = off), or {} to read it back"};
        for (std::size_t i = 0; i < ids_.size(); ++i)
            if (auto st = set_watchdog(i, static_cast<int>(*ms)); !st.ok()) return st;
        return ValueMap{{"ms", *ms}};
    }
    if (verb == "ping") {
        if (!bus_) return Error{ErrorCode::state_error, "ping: the bus is not open (configure first)"};
        ValueMap out;
        for (std::size_t i = 0; i < ids_.size(); ++i) {
            auto p = bus_->ping(ids_[i]);
            if (!p.ok()) return with_joint(i, p.status());
            out[config_.joints[i].name] = static_cast<std::int64_t>(p->model_number);
        }
        return out;
    }
    if (verb == "statistics") {
        if (!bus_) return Error{ErrorCode::state_error, "statistics: the bus is not open"};
        const auto& s = bus_->statistics();
        return ValueMap{{"transactions", static_cast<std::int64_t>(s.transactions)},
                        {"retries", static_cast<std::int64_t>(s.retries)},
                        {"timeouts", static_cast<std::int64_t>(s.timeouts)},
                        {"crc_errors", static_cast<std::int64_t>(s.crc_errors)},
                        {"stale_replies", static_cast<std::int64_t>(s.stale_replies)},
                        {"bytes_sent", static_cast<std::int64_t>(s.bytes_sent)},
                        {"bytes_received", static_cast<std::int64_t>(s.bytes_received)}};
    }
    return Error{ErrorCode::unsupported, "no operation '" + verb + "' (dynamixel knows: reboot, ping, watchdog, rest, statistics)"};
}

}  // namespace rollsense::dynamixel
