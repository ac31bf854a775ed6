// The palm-parallel controller (the paper's "palm width controller"): while
// the pushing finger clamps the object in current mode, drive the palm width
// so that the pushing finger's angle tracks the sensing finger's angle, i.e.
// the fingers stay parallel as the object rolls.
//
// Why this law. With parallel fingers at angle θ the palm width that fits an
// object of effective width d is w = d / cos θ, so as the sensing finger
// turns at θ̇ the width must change at ẇ = w·tan θ·θ̇ (feedforward; needs no
// knowledge of d). Whatever that misses — d changing as a prism tumbles,
// servo lag, a wrong start width — shows up as the pushing finger lagging
// (palm too narrow: the object holds it more open, at a lower angle) or
// leading (palm too wide). The feedback term widens the palm in proportion
// to the lag:  ẇ = w·tan θs·θ̇s + gain·(θs − θp).
// The palm goal is integrated from ẇ, rate-limited, kept within `lead` mm of
// the measured width (no wind-up while the servo is blocked) and inside the
// palm joint's limits. Without a clamp (pushing finger not in current mode)
// there is nothing to track: the controller stops the palm where it is, and
// does the same when it is switched off.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "runtime/control/controller.hpp"
#include "runtime/robot/robot.hpp"

namespace rollsense::runtime {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

struct PalmParallelSettings {
    std::string sensing, pushing, palm;
    double gain = 4.0;         // mm/s of palm width per degree of lag
    bool feedforward = true;
    double max_speed = 40.0;   // mm/s
    double lead = 5.0;         // mm the goal may run ahead of the measured width
};

class PalmParallel final : public Controller {
public:
    explicit PalmParallel(PalmParallelSettings s) : s_(std::move(s)) {}

    Status enable(double, JointAccess& joints) override {
        for (const auto* name : {&s_.sensing, &s_.pushing, &s_.palm})
            if (!joints.state(*name))
                return {ErrorCode::not_found, "no joint '" + *name + "' (set controllers.palm_parallel." +
                                                  (name == &s_.sensing   ? "sensing"
                                                   : name == &s_.pushing ? "pushing"
                                                                         : "palm") +
                                                  " in the profile)"};
        const JointInfo* palm = joints.info(s_.palm);
        if (palm->unit != "mm")
            return {ErrorCode::invalid_argument, "joint '" + s_.palm + "' is in " + palm->unit +
                                                     "; the palm must be a width in mm (set "
                                                     "controllers.palm_parallel.palm to the palm-width joint)"};
        goal_ = joints.state(s_.palm)->position;
        error_deg_ = 0.0;
        rate_ = 0.0;
        commanding_ = false;
        return {};
    }

    void disable(double, JointAccess& joints) override { stop_palm(joints); }

    Status update(double, double dt, JointAccess& joints) override {
        const JointState& sensing = *joints.state(s_.sensing);
        const JointState& pushing = *joints.state(s_.pushing);
        const JointState& palm = *joints.state(s_.palm);
        const JointLimit* limit = joints.limit(s_.palm);
        tracking_ = pushing.mode == ControlMode::current && pushing.torque_enabled;
        error_deg_ = sensing.position - pushing.position;
        if (!tracking_ || dt <= 0.0) {
            rate_ = 0.0;
            goal_ = palm.position;
            stop_palm(joints);  // once, when the clamp ends; then scripts own the palm again
            return {};
        }
        const double feedforward =
            s_.feedforward ? palm.position * std::tan(sensing.position * kRadPerDeg) * sensing.velocity * kRadPerDeg
                           : 0.0;
        const double max_speed = speed_limit(limit);
        rate_ = std::clamp(feedforward + s_.gain * error_deg_, -max_speed, max_speed);
        goal_ = std::clamp(goal_ + rate_ * dt, palm.position - s_.lead, palm.position + s_.lead);
        if (limit) goal_ = std::clamp(goal_, limit->min, limit->max);

        commanding_ = true;
        return joints.set_command(s_.palm, palm_command(joints, goal_, max_speed));
    }

    std::map<std::string, double> telemetry() const override {
        return {{"error_deg", error_deg_}, {"palm_goal_mm", goal_}, {"palm_rate_mm_s", rate_},
                {"tracking", tracking_ ? 1.0 : 0.0}};
    }

private:
    double speed_limit(const JointLimit* limit) const {
        return limit && limit->max_velocity > 0 ? std::min(s_.max_speed, limit->max_velocity) : s_.max_speed;
    }

    JointCommand palm_command(JointAccess& joints, double position, double speed) const {
        JointCommand c;
        c.mode = position_mode_of(*joints.info(s_.palm));
        c.position = position;
        c.profile_velocity = speed;
        return c;
    }

    // Replace the last goal (up to `lead` mm ahead) by the measured width.
    // Best effort: refused while commands are locked (emergency stop), when
    // the kernel's safe state holds every joint anyway.
    void stop_palm(JointAccess& joints) {
        if (!commanding_) return;
        commanding_ = false;
        const JointState* palm = joints.state(s_.palm);
        const JointLimit* limit = joints.limit(s_.palm);
        if (!palm) return;
        double here = palm->position;
        if (limit) here = std::clamp(here, limit->min, limit->max);
        (void)joints.set_command(s_.palm, palm_command(joints, here, speed_limit(limit)));
    }

    PalmParallelSettings s_;
    double goal_ = 0.0;
    double error_deg_ = 0.0;
    double rate_ = 0.0;
    bool tracking_ = false;
    bool commanding_ = false;  // the palm's command is ours
};

ParamSchema palm_parallel_schema() {
    return {
        param_string("sensing", "sensing_finger", "joint of the sensing finger (position mode, deg)"),
        param_string("pushing", "pushing_finger", "joint of the pushing finger (current mode while clamped, deg)"),
        param_string("palm", "palm", "joint of the palm width (mm)"),
        param_number("gain", 4.0, "palm speed per degree the pushing finger lags the sensing finger", 0, {},
                     "mm/s/deg"),
        param_bool("feedforward", true, "add the parallel-finger width rate w*tan(theta)*dtheta/dt"),
        param_number("max_speed", 40.0, "palm speed limit (the palm joint's max_velocity applies too)", 0.1, {},
                     "mm/s"),
        param_number("lead", 5.0, "how far the palm goal may run ahead of the measured width", 0.1, {}, "mm"),
    };
}

const ControllerRegistration kPalmParallel{ControllerType{
    "palm_parallel",
    "keeps the fingers parallel: drives the palm width so the pushing finger's angle tracks the sensing finger's",
    palm_parallel_schema(),
    [](const ParamSet& p) -> std::unique_ptr<Controller> {
        PalmParallelSettings s;
        s.sensing = p.get_string("sensing");
        s.pushing = p.get_string("pushing");
        s.palm = p.get_string("palm");
        s.gain = p.get_number("gain");
        s.feedforward = p.get_bool("feedforward");
        s.max_speed = p.get_number("max_speed");
        s.lead = p.get_number("lead");
        return std::make_unique<PalmParallel>(std::move(s));
    }}};

}  // namespace
}  // namespace rollsense::runtime
