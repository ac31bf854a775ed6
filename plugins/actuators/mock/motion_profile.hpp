// A one-dimensional trapezoidal motion profile, as an X-series Dynamixel
// follows it in position mode: accelerate at the profile acceleration to the
// profile velocity, cruise, decelerate to stop exactly at the goal. A new goal
// during a motion re-plans from the present position and velocity.
#pragma once

#include <vector>

namespace rollsense::mock {

struct MotionSample {
    double position = 0;
    double velocity = 0;
    bool moving = false;
};

class MotionProfile {
public:
    // Plan from (position, velocity) at time t0 to `goal`. velocity_limit and
    // acceleration use the servo's convention: 0 means unlimited.
    void plan(double t0, double position, double velocity, double goal, double velocity_limit, double acceleration);
    // Hold still at `position` from now on.
    void stop(double t0, double position);
    MotionSample at(double t) const;
    double end_time() const { return end_time_; }
    double goal() const { return goal_; }

private:
    struct Segment {
        double t0, p0, v0, a, duration;
    };
    void add(double& t, double& p, double& v, double a, double duration);

    std::vector<Segment> segments_;
    double start_time_ = 0;
    double end_time_ = 0;
    double goal_ = 0;
};

}  // namespace rollsense::mock
