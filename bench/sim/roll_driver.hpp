// Drives a sensor the way the paper's roll script and a Dynamixel position
// profile would (method.md §2, simulation.md §4), for the bench and the tests:
// begin_trial → start_recording → sensing finger -44° → +44° with a trapezoidal
// profile at profile velocity 10/15/20 units → settle → stop_recording, sampled
// at 31.1 Hz. The sensor only ever sees the joint states, as under the kernel.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "rollsense/sensor.hpp"

namespace rollsense::sim::bench {

struct RollPlan {
    double profile_velocity = 10.0;      // Dynamixel units (0.229 rev/min each)
    double profile_acceleration = 100.0; // Dynamixel units (214.577 rev/min² each)
    double start_deg = -44.0, end_deg = 44.0;
    double speed_factor = 1.0;           // actuator's speed error (≈ 1 % jitter)
    double lead_in = 0.08;               // s recorded before the finger starts
    double settle = 0.12;                // s recorded after it stops
    double clamp_current = 120.0;        // mA on the pushing finger (share/lua/etroll.lua's clamp_current)
    double rate = 31.1;                  // Hz
};

// Trapezoidal position profile (what the servo's profile generator does).
class TrapezoidProfile {
public:
    TrapezoidProfile(double from, double to, double velocity, double acceleration)
        : from_(from), dir_(to >= from ? 1.0 : -1.0), dist_(std::abs(to - from)), v_(velocity), a_(acceleration) {
        if (dist_ < v_ * v_ / a_) v_ = std::sqrt(dist_ * a_);  // never reaches full speed
        ta_ = v_ / a_;
        duration_ = 2.0 * ta_ + (dist_ - v_ * ta_) / v_;
    }
    double duration() const { return duration_; }
    double position(double t) const {
        double s;
        if (t <= 0.0) s = 0.0;
        else if (t < ta_) s = 0.5 * a_ * t * t;
        else if (t < duration_ - ta_) s = 0.5 * a_ * ta_ * ta_ + v_ * (t - ta_);
        else if (t < duration_) s = dist_ - 0.5 * a_ * (duration_ - t) * (duration_ - t);
        else s = dist_;
        return from_ + dir_ * s;
    }

private:
    double from_, dir_, dist_, v_, a_, ta_ = 0.0, duration_ = 0.0;
};

struct Recording {
    std::array<std::vector<double>, 3> channels;
    std::vector<double> time;
    std::vector<double> finger;  // deg
};

inline Status record_roll(Sensor& sensor, const TrialInfo& trial, const RollPlan& plan, Recording& rec) {
    const double deg_per_unit_velocity = 0.229 * 6.0;       // rev/min → deg/s
    const double deg_per_unit_acceleration = 214.577 * 0.1;  // rev/min² → deg/s²
    const TrapezoidProfile profile(plan.start_deg, plan.end_deg,
                                   plan.profile_velocity * deg_per_unit_velocity * plan.speed_factor,
                                   plan.profile_acceleration * deg_per_unit_acceleration);
    const std::vector<std::string> names{"sensing_finger", "pushing_finger", "palm"};
    std::vector<JointState> states(3);
    SampleInput in;
    in.joint_names = &names;
    in.joint_states = &states;
    auto set_time = [&](double t) {
        in.time = t;
        states[0].position = profile.position(t - plan.lead_in);
        states[0].moving = t > plan.lead_in && t < plan.lead_in + profile.duration();
        states[1].position = states[0].position;
        states[1].current = plan.clamp_current;
        states[1].mode = ControlMode::current;
        states[2].position = 65.0;
    };
    for (auto& c : rec.channels) c.clear();
    rec.time.clear();
    rec.finger.clear();
    if (auto st = sensor.begin_trial(trial); !st) return st;
    set_time(0.0);
    if (auto st = sensor.start_recording(in); !st) return st;
    const double stop = plan.lead_in + profile.duration() + plan.settle;
    Frame frame;
    for (int k = 0;; ++k) {
        const double t = k / plan.rate;
        if (t > stop) break;
        set_time(t);
        frame.values.assign(3, 0.0);
        if (auto st = sensor.read(in, frame); !st) return st;
        for (std::size_t c = 0; c < 3; ++c) rec.channels[c].push_back(frame.values[c]);
        rec.time.push_back(t);
        rec.finger.push_back(states[0].position);
    }
    if (auto st = sensor.stop_recording(); !st) return st;
    return sensor.end_trial();
}

}  // namespace rollsense::sim::bench
