// The `dynamixel` actuator: every joint of one Protocol 2.0 bus.
//
// Per control period it sends exactly one SYNC_WRITE (Goal Current .. Goal
// Position for every servo) and one SYNC_READ (Moving .. Present Position);
// single-servo WRITEs happen only for what changes rarely (operating mode,
// torque), a READ of Hardware Error Status only after a servo raised its
// alert bit, and a READ of Bus Watchdog only after a pause in the periods
// long enough to have tripped it.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "dynamixel_config.hpp"
#include "in_process_emulator.hpp"
#include "rollsense/actuator.hpp"
#include "rollsense/hal/dynamixel/bus.hpp"

namespace rollsense::dynamixel {

class DynamixelActuator final : public Actuator {
public:
    ~DynamixelActuator() override;
    Status on_configure(const ParamSet& params, const PluginContext& context) override;
    Status on_activate() override;
    Status on_deactivate() override;
    Status on_cleanup() override;
    Status on_recover() override;
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    std::vector<JointInfo> joints() const override { return infos_; }
    Status read(double time, std::span<JointState> states) override;
    Status write(double time, std::span<const JointCommand> commands) override;

    // For benches and diagnostics: nullptr before configure.
    const hal::dxl::Bus* bus() const { return bus_.get(); }

private:
    struct Runtime {
        ControlMode mode = ControlMode::position;
        bool torque = false;
        std::int32_t present_ticks = hal::dxl::kCentreTick;
        std::uint8_t hardware_error = 0;
        bool hardware_error_told = false;  // reported (the run's error, or a warning for a released joint)
        // The servo's own limits, as read back at prepare(): a SYNC_WRITE has
        // no reply, so a value the servo would refuse must be caught here.
        std::int32_t velocity_limit = 0;
        std::int32_t min_ticks = 0, max_ticks = 4095;
        // Its Bus Watchdog was read as tripped (-1): goals are read-only until 98 is written 0.
        bool watchdog_tripped = false;
    };

    std::string who(std::size_t i) const;
    // A servo's failure, named by its joint; a failure of the port itself (bus_->port_failed()) is the port's:
    // it gets the way out of port_failure() instead.
    Status with_joint(std::size_t i, Status st) const;
    // The port failed (adapter pulled, emulator gone): its error, with the way out.
    Status port_failure(Status st) const;
    Status check_servos();
    // EEPROM items the joint needs in `mode` (mode, current limit, position
    // limits); turns torque off only if something has to change.
    Status prepare(std::size_t i, ControlMode mode);
    // Goal = present position (or zero current), then torque on.
    Status hold_here(std::size_t i);
    // A joint's min..max in ticks, low first; the position limits servo i has once in position mode.
    static std::pair<std::int32_t, std::int32_t> tick_range(const JointMap& j);
    std::pair<std::int32_t, std::int32_t> position_limits_after_switch(std::size_t i) const;
    Status set_torque(std::size_t i, bool on);
    // Hardware error check, watchdog, EEPROM items, hold here, watchdog armed.
    Status activate_servo(std::size_t i);
    // Bus Watchdog off and torque off on every servo; those that did not confirm
    // (no reply, a corrupt one) get both again without a reply asked for.
    // Returns the servos that did not confirm, with why, and how the resend went (ok: sent, or none needed).
    using Unconfirmed = std::pair<std::size_t, Status>;
    struct Release {
        std::vector<Unconfirmed> servos;
        Status resend;
    };
    Release release_servos();
    // The servos not known to be released, named (with their errors, or only
    // their kinds when the fault was reported already); ok if none.
    Status not_confirmed(const Release& release, bool with_reasons) const;
    // Bus Watchdog (98): clear a tripped one (it is logged: the last run ended
    // without telling the servo), then set it to `ms` (0 = off).
    Status set_watchdog(std::size_t i, int ms);
    // The fault of a servo whose Bus Watchdog tripped during the run.
    Status watchdog_fault(std::size_t i) const;
    Status reboot_joint(std::size_t i);
    // How to clear servo i's latched hardware error: the `rollsense dxl reboot` command line with this bus's
    // port, baud and the servo's id (the one way when no script runs, as at activation); with `in_script`, the
    // Lua call a script that carries on can make too.
    std::string reboot_way_out(std::size_t i, bool in_script) const;
    Result<std::size_t> joint_index(const ValueMap& args) const;
    // A torque-off SYNC_WRITE for every servo, written from the crash handler
    // (hal/dynamixel/last_resort.hpp); registered while the bus is open and active.
    void arm_last_resort();
    void disarm_last_resort();
    int last_resort_slot_ = -1;
    // Set by invoke("rest"): the next write re-arms every servo's Bus Watchdog.
    bool rearm_watchdog_ = false;
    // The Bus Watchdog last set on the servos (ms, 0 = off), and the time of
    // the last read() or write(): only a pause longer than half of it can have
    // tripped a watchdog, so only then does read() look at address 98.
    int watchdog_ms_ = 0;
    double last_io_time_ = 0.0;

    // "<profile file>: devices.<name>.params", the start of a configuration refusal.
    std::string where_;
    BusConfig config_;
    std::vector<JointInfo> infos_;
    std::vector<std::uint8_t> ids_;
    std::vector<Runtime> rt_;
    std::unique_ptr<hal::dxl::Bus> bus_;
    // device "emulator" only: the in-memory line bus_ owns, whose servos read() moves on.
    hal::dxl::VirtualBusLink* emulator_ = nullptr;
};

}  // namespace rollsense::dynamixel
