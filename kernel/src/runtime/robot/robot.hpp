// The hand as the kernel sees it: every device of a profile, created through the plugin registry and driven through
// lifecycle handles, plus the joint table on which limits are enforced. The control loop (control_tick) and the
// sampling loop (sample) are C++; Lua only sets commands.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "rollsense/dataset.hpp"
#include "runtime/control/controller.hpp"
#include "runtime/plugin/plugin_registry.hpp"
#include "runtime/profile/profile.hpp"

namespace rollsense::runtime {

struct Joint {
    std::string name;
    ActuatorHandle* actuator = nullptr;
    std::size_t index = 0;  // in the actuator's joints()
    JointInfo info;         // as the device declares it
    JointLimit limit;       // enforced by the kernel (profile limits within the device's)
    JointCommand command;
    JointState state;
};

// The position mode a joint holds and moves in: extended position where that is the joint's default (a multi-turn
// winch), plain position otherwise.
ControlMode position_mode_of(const JointInfo& info);
// "Stay where you are": the joint's position mode at its present position, clamped into its limits. Used on activation,
// for the safe state and by hold().
JointCommand hold_command(const Joint& joint);

// A profile's device with its plugin found (a sensor or an actuator) and its parameters checked against the plugin's
// schema: all that needs no hardware (Robot::create's first step; `rollsense run --check` stops here).
struct ResolvedDevice {
    std::shared_ptr<const LoadedLibrary> library;
    ParamSet params;
};
Result<ResolvedDevice> resolve_device(const Profile& profile, const DeviceSpec& device, PluginRegistry& registry);

class Robot final : public JointAccess {
public:
    // Creates and configures every device of the profile (parameters checked against each plugin's schema). Nothing
    // moves yet.
    static Result<std::unique_ptr<Robot>> create(const Profile& profile, PluginRegistry& registry,
                                                 const std::filesystem::path& share_dir);
    ~Robot() override;

    // Activate every device; each joint then holds where it is.
    Status activate(double time);
    // Best effort, never throws: stop every joint (hold, or torque off where the profile says so), then deactivate (or
    // recover, if failed) and clean up every device.
    bool shutdown(double time, bool keep_released = false) noexcept;  // false: a device did not deactivate (logged)
    // Stop every joint now: the profile's safe action (hold here, or torque off) to every actuator that is active or
    // failed, so the servos that still answer stop even when another one on their bus does not. Used on any failure,
    // a cancel, the e-stop and a script's normal end (keep_released: the joints it released stay released).
    void safe_state(double time, bool keep_released = false) noexcept;
    // Refuse every command until released (emergency stop).
    void set_commands_locked(bool locked, std::string reason = {});
    std::string commands_locked_reason() const { return locked_ ? lock_reason_ : std::string(); }  // "": not locked

    // Held on the script's thread around actuator I/O (activate, control_tick, safe_state, shutdown; device:call and
    // :recover), and by the cancel watchdog's thread, with a timeout, for its safe state (Session::last_resort).
    // Sensors are not under it: the safe state never reads them.
    std::unique_lock<std::recursive_timed_mutex> lock_devices() { return std::unique_lock(devices_mutex_); }
    std::recursive_timed_mutex& devices_mutex() { return devices_mutex_; }

    // One control period: read all actuators, run enabled controllers, write.
    Status control_tick(double time, double dt);
    // One sample of every sensor, appended to `data` (channels, joints, valid).
    Status sample(double time, TrialData& data);

    // The dataset columns this robot records.
    const std::vector<std::string>& channel_columns() const { return channel_columns_; }
    const std::vector<std::string>& channel_units() const { return channel_units_; }
    const std::vector<std::string>& recorded_joints() const { return recorded_joints_; }

    // Sensors' trial hooks.
    Status begin_trial(const TrialInfo& trial);
    Status start_recording(double time);
    Status stop_recording();
    Status end_trial();

    // Joint table.
    Joint* find_joint(const std::string& name);
    const Joint* find_joint(const std::string& name) const;
    const std::vector<Joint>& joints() const { return joints_; }
    std::string joint_names() const;  // "a, b, c" for messages
    // Check a command against the joint's limits and store it for the next write.
    Status command_joint(Joint& joint, const JointCommand& command);

    // Controllers from the profile.
    Status enable_controller(const std::string& name, double time);
    void disable_controller(const std::string& name, double time);
    void disable_all_controllers(double time);
    Controller* find_controller(const std::string& name);
    bool controller_enabled(const std::string& name) const;
    // What moves between control periods without a new command ("joint 'palm' is driven by current"); "" if nothing.
    std::string unattended_motion() const;

    // Devices by name, for `device:call(...)` from scripts.
    ComponentHandle* find_device(const std::string& name);
    std::vector<std::string> device_names() const;

    // JointAccess (for controllers).
    const JointState* state(const std::string& joint) const override;
    const JointInfo* info(const std::string& joint) const override;
    const JointCommand* command(const std::string& joint) const override;
    const JointLimit* limit(const std::string& joint) const override;
    Status set_command(const std::string& joint, const JointCommand& command) override;

private:
    Robot() = default;
    Status read_actuators(double time);
    Status write_actuators(double time);
    // The profile's safe action for each joint of `actuator`, into `out` (one per joint).
    void safe_commands(const ActuatorHandle& actuator, std::vector<JointCommand>& out, bool keep_released) const;
    SampleInput sample_input(double time);

    struct ActuatorSlot {
        std::unique_ptr<ActuatorHandle> handle;
        std::vector<std::size_t> joints;  // indices into joints_
        std::vector<JointState> states;   // scratch, reused every period
        std::vector<JointCommand> commands;
    };
    struct SensorSlot {
        std::unique_ptr<SensorHandle> handle;
        std::vector<ChannelInfo> channels;  // as the plugin described them once
        Frame frame;  // scratch
    };
    struct ControllerSlot {
        std::string name;
        std::unique_ptr<Controller> controller;
        bool enabled = false;
    };

    std::string profile_label_;
    std::vector<ActuatorSlot> actuators_;
    std::vector<SensorSlot> sensors_;
    std::vector<ControllerSlot> controllers_;
    std::vector<Joint> joints_;
    std::vector<std::string> joint_names_;       // for SampleInput
    std::vector<JointState> joint_states_;       // for SampleInput: a view filled from joints_
    std::vector<std::string> channel_columns_;
    std::vector<std::string> channel_units_;     // per channel column
    std::vector<std::string> recorded_joints_;
    std::vector<std::size_t> recorded_joint_index_;
    bool locked_ = false;
    std::string lock_reason_;
    std::vector<std::string> safe_reports_;  // the safe state runs again and again after a fault: each failure once
    std::recursive_timed_mutex devices_mutex_;
};

}  // namespace rollsense::runtime
