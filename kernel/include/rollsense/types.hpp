// Plain data exchanged between the kernel and plugins: joint states and
// commands, sensor frames, trial descriptions. No behaviour, no dependencies.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rollsense {

// ----------------------------------------------------------------- joints --

// How a joint is driven. Values follow the Dynamixel X-series operating modes
// where one exists, so a servo plugin can map them one to one.
enum class ControlMode {
    position,                // goal position with a trapezoidal profile (profile velocity/acceleration)
    extended_position,       // multi-turn position (the winch)
    velocity,                // goal velocity
    current,                 // goal current (torque): clamps an object
    current_based_position,  // position goal with a current ceiling
};

std::string_view to_string(ControlMode mode) noexcept;

// Static description of one joint, as the actuator reports it. Units: a revolute joint uses degrees, a linear one
// millimetres; velocities are unit/s, accelerations unit/s^2, currents mA.
struct JointInfo {
    std::string name;
    std::string unit = "deg";  // "deg" or "mm"
    double min_position = -180.0;
    double max_position = 180.0;
    double max_velocity = 0.0;  // 0 = no limit declared by the device
    double max_current = 0.0;   // mA, 0 = no current control
    std::vector<ControlMode> modes{ControlMode::position};
};

// One joint command for one control period.
struct JointCommand {
    ControlMode mode = ControlMode::position;
    double position = 0.0;              // goal (position modes)
    double velocity = 0.0;              // goal velocity (velocity mode)
    double current = 0.0;               // goal current, mA (current modes: the ceiling)
    double profile_velocity = 0.0;      // unit/s, 0 = device maximum
    double profile_acceleration = 0.0;  // unit/s^2, 0 = infinite
    bool torque_enabled = true;
};

// One joint's measured state.
struct JointState {
    double position = 0.0;
    double velocity = 0.0;
    double current = 0.0;          // mA
    bool moving = false;           // a motion profile is still running
    bool torque_enabled = false;
    ControlMode mode = ControlMode::position;
    std::uint32_t fault_bits = 0;  // device-specific hardware error bits, 0 = healthy
    std::string fault;             // human-readable fault, empty = healthy
};

// ---------------------------------------------------------------- sensors --

struct ChannelInfo {
    std::string name;         // column name in recorded files, e.g. "ch1"
    std::string unit;         // "1" for the paper's unitless reading, "kPa", "degC"
    std::string description;  // one line
};

// One sample of every channel of a sensor.
struct Frame {
    double time = 0.0;           // seconds on the run clock
    std::vector<double> values;  // one per channel, in channels() order
    bool valid = true;           // false: a read failed; `reason` says why, values may be NaN
    std::string reason;
};

// What the kernel hands a sensor with every sample: the time and the joint states measured in the same control
// period. A sensor that depends on the hand's posture (the simulation; a replay that checks the commanded roll) reads
// them here rather than keeping a private copy of the schedule.
struct SampleInput {
    double time = 0.0;
    const std::vector<std::string>* joint_names = nullptr;
    const std::vector<JointState>* joint_states = nullptr;

    // Position of a joint by name; nullptr if there is no such joint.
    const JointState* joint(const std::string& name) const {
        if (!joint_names || !joint_states) return nullptr;
        for (std::size_t i = 0; i < joint_names->size(); ++i)
            if ((*joint_names)[i] == name) return &(*joint_states)[i];
        return nullptr;
    }
};

// ----------------------------------------------------------------- trials --

// The description of one trial, set by the roll script before it rolls. Sensors use it to prepare (the simulation
// places the object; a replay picks the recording); the recorder writes it into the dataset's manifest.
struct TrialInfo {
    std::string id;                           // unique within a dataset, e.g. "C1-s10-r007"
    std::string object;                       // catalogue id, e.g. "C1"
    std::string speed;                        // speed label, e.g. "10" (profile velocity units)
    int repetition = 0;
    std::uint64_t seed = 0;                   // per-trial seed derived from the run seed
    std::map<std::string, std::string> extra; // free-form metadata from the script
};

}  // namespace rollsense
