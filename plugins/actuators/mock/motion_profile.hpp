// A one-dimensional trapezoidal motion profile, as an X-series Dynamixel
// follows it in position mode: accelerate at the profile acceleration to the
// profile velocity, cruise, decelerate to stop exactly at the goal. A new goal
// during a motion re-plans from the present position and velocity.
//
// Times inside a plan are kept relative to its start (a point of the virtual
// clock's grid) and `at` subtracts that start first: the arithmetic is then the
// same whenever the plan starts, so a trial records the same bytes whether it is
// the first of a run or the thousandth, resumed or in a shard. (Absolute segment
// times, t0 + duration, round differently at different clock magnitudes, and the
// barometers' counts turn a last-bit difference into a whole count now and then.)
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
    double end_time() const { return start_time_ + duration_; }
    double goal() const { return goal_; }

private:
    struct Segment {
        double offset, p0, v0, a, duration;  // offset: from the plan's start
    };
    void add(double& p, double& v, double a, double duration);

    std::vector<Segment> segments_;
    double start_time_ = 0;
    double duration_ = 0;  // of the whole plan
    double goal_ = 0;
};

}  // namespace rollsense::mock
