// Actuator plugin interface.
//
// The kernel's control loop calls read() then write() once per control period for all joints of an actuator at once
// (a servo bus does one sync read and one sync write). Limits from the profile are enforced by the kernel before
// write() is called; a plugin may enforce its device's own limits as well. On activation an actuator must hold its
// present position (no jump to a stale goal): the kernel also re-reads the state and commands "hold here".
#pragma once

#include <span>
#include <vector>

#include "rollsense/component.hpp"
#include "rollsense/types.hpp"

namespace rollsense {

class ROLLSENSE_API Actuator : public Component {
public:
    // Fixed after on_configure.
    virtual std::vector<JointInfo> joints() const = 0;

    // Measured state of every joint at `time` (run clock, seconds).
    virtual Status read(double time, std::span<JointState> states) = 0;
    // One command per joint, in joints() order.
    virtual Status write(double time, std::span<const JointCommand> commands) = 0;
};

}  // namespace rollsense
