#include "motion_profile.hpp"

#include <algorithm>
#include <cmath>

namespace rollsense::mock {

void MotionProfile::add(double& p, double& v, double a, double duration) {
    if (duration <= 0) return;
    segments_.push_back({duration_, p, v, a, duration});
    p += v * duration + 0.5 * a * duration * duration;
    v += a * duration;
    duration_ += duration;
}

void MotionProfile::stop(double t0, double position) {
    segments_.clear();
    start_time_ = t0;
    duration_ = 0;
    goal_ = position;
}

void MotionProfile::plan(double t0, double p, double v, double goal, double vmax, double amax) {
    stop(t0, goal);
    const double distance = goal - p;
    if (vmax <= 0 && amax <= 0) return;  // both unlimited: the servo jumps (as fast as it can)
    if (amax <= 0) {  // unlimited acceleration: constant velocity to the goal
        v = distance >= 0 ? vmax : -vmax;
        add(p, v, 0.0, std::abs(distance) / vmax);
        return;
    }
    if (vmax <= 0) vmax = 1e9;
    const double dir = distance >= 0 ? 1.0 : -1.0;
    // Moving away from the goal, or too fast to stop before it: brake to rest first.
    const double stopping = v * v / (2 * amax);
    if ((v != 0 && (v > 0) != (dir > 0)) || stopping > std::abs(distance)) {
        add(p, v, v > 0 ? -amax : amax, std::abs(v) / amax);
        v = 0;
        const double rest_distance = goal - p;
        const double d2 = rest_distance >= 0 ? 1.0 : -1.0;
        const double D = std::abs(rest_distance);
        const double peak = std::min(vmax, std::sqrt(amax * D));
        const double t_acc = peak / amax;
        const double d_cruise = D - peak * peak / amax;
        add(p, v, d2 * amax, t_acc);
        add(p, v, 0.0, d_cruise / peak);
        add(p, v, -d2 * amax, t_acc);
    } else {
        double v0 = std::min(std::abs(v), vmax);
        v = dir * v0;
        const double D = std::abs(distance);
        const double d_acc = (vmax * vmax - v0 * v0) / (2 * amax);
        const double d_dec = vmax * vmax / (2 * amax);
        if (d_acc + d_dec <= D) {
            add(p, v, dir * amax, (vmax - v0) / amax);
            add(p, v, 0.0, (D - d_acc - d_dec) / vmax);
            add(p, v, -dir * amax, vmax / amax);
        } else {
            const double peak = std::sqrt((2 * amax * D + v0 * v0) / 2);
            add(p, v, dir * amax, (peak - v0) / amax);
            add(p, v, -dir * amax, peak / amax);
        }
    }
}

MotionSample MotionProfile::at(double t) const {
    const double since_start = t - start_time_;  // exact: both on the clock's grid
    if (since_start >= duration_ || segments_.empty()) return {goal_, 0.0, since_start < duration_};
    for (const auto& s : segments_) {
        const double dt = since_start - s.offset;
        if (dt <= s.duration) {
            if (dt < 0) return {s.p0, s.v0, true};
            return {s.p0 + s.v0 * dt + 0.5 * s.a * dt * dt, s.v0 + s.a * dt, true};
        }
    }
    return {goal_, 0.0, false};
}

}  // namespace rollsense::mock
