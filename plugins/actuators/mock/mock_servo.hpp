// One modelled servo joint. Position modes follow a trapezoidal profile; in
// current mode the joint moves toward the side the current pushes at a speed
// proportional to the current and stops against a modelled contact, where it
// holds with the commanded current (like a finger clamping an object).
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "motion_profile.hpp"
#include "rollsense/types.hpp"

namespace rollsense::mock {

struct ServoModel {
    double min_position = -180, max_position = 180;
    double free_speed_per_ma = 0.05;  // unit/s per mA in current mode before contact
    double moving_current = 20;       // mA reported while a profile runs (not a dynamics model)
    double contact = std::numeric_limits<double>::quiet_NaN();  // NaN: no contact, stops at a limit
};

class MockServo {
public:
    MockServo(ServoModel model, double initial_position);

    JointState state(double t) const;
    // The same, written over `s`: the read of every control period reuses the
    // caller's states, and its fault text is copied only when it changed.
    void state(double t, JointState& s) const;
    // Apply a command at time t (re-plans only when the command changed).
    void command(double t, const JointCommand& c);
    void set_contact(double position) { model_.contact = position; }
    void inject_fault(double t, const std::string& fault);
    void clear_fault(double t);
    const ServoModel& model() const { return model_; }

private:
    double current_mode_position(double since_command) const;

    ServoModel model_;
    JointCommand last_{};
    bool has_command_ = false;
    MotionProfile profile_;
    // current / velocity mode: motion since t0 from p0
    double t0_ = 0, p0_ = 0;
    bool torque_ = false;
    std::string fault_;
};

}  // namespace rollsense::mock
