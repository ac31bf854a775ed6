// Conformance tests every plugin of a kind runs (the YARP idea: one contract,
// one suite, every driver and its fake twin pass it). Header-only; call from a
// Catch2 TEST_CASE:
//
//     rollsense::testing::SensorConformance c;
//     c.make = [] { return std::make_unique<MySensor>(); };
//     c.params = ...;                     // validated ParamSet
//     c.joint_names = {"sensing_finger"}; // the joints the sensor reads, and
//     c.joints = [](double t) { ... };    // their states at time t (none offered otherwise)
//     rollsense::testing::check_sensor_conformance(c);
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "rollsense/actuator.hpp"
#include "rollsense/sensor.hpp"

namespace rollsense::testing {

// ------------------------------------------------------------------ sensor --

struct SensorConformance {
    std::function<std::unique_ptr<Sensor>()> make;
    ParamSet params;
    PluginContext context;
    TrialInfo trial{"conformance-1", "C1", "10", 1, 42, {}};
    int frames = 40;
    double period = 1.0 / 31.1;
    // Joint states offered with each sample (e.g. a sensing finger sweeping):
    // a sensor that reads input.joint(name) needs that name here, or every
    // frame it reads is invalid and the suite fails.
    std::vector<std::string> joint_names;
    std::function<std::vector<JointState>(double time)> joints;
    // Channels that must read valid in every frame (false for fault-injection runs).
    bool expect_all_valid = true;
};

inline void run_sensor_recording(Sensor& s, const SensorConformance& c, std::vector<Frame>& frames) {
    std::vector<JointState> states;
    SampleInput in;
    in.joint_names = &c.joint_names;
    in.joint_states = &states;
    const auto n_channels = s.channels().size();
    REQUIRE(s.begin_trial(c.trial).ok());
    in.time = 0.0;
    if (c.joints) states = c.joints(0.0);
    REQUIRE(s.start_recording(in).ok());
    frames.clear();
    for (int i = 0; i < c.frames; ++i) {
        in.time = i * c.period;
        if (c.joints) states = c.joints(in.time);
        Frame f;
        f.time = in.time;
        f.values.assign(n_channels, 0.0);
        auto st = s.read(in, f);
        INFO("frame " << i << ": " << st.message());
        REQUIRE(st.ok());
        frames.push_back(std::move(f));
    }
    REQUIRE(s.stop_recording().ok());
    REQUIRE(s.end_trial().ok());
}

inline void check_sensor_conformance(const SensorConformance& c) {
    REQUIRE(c.make);
    auto s = c.make();
    REQUIRE(s);

    // configure → describes its channels
    {
        auto st = s->on_configure(c.params, c.context);
        INFO("on_configure: " << st.message());
        REQUIRE(st.ok());
    }
    const auto channels = s->channels();
    REQUIRE_FALSE(channels.empty());
    std::set<std::string> names;
    for (const auto& ch : channels) {
        CHECK_FALSE(ch.name.empty());
        CHECK(ch.name.find_first_of(", \"\n") == std::string::npos);  // usable as a CSV column name
        CHECK(names.insert(ch.name).second);                           // unique
        CHECK_FALSE(ch.unit.empty());
    }
    // channels are fixed after configure
    CHECK(s->channels().size() == channels.size());

    // activate → record: one value per channel, valid frames finite, invalid ones explained
    REQUIRE(s->on_activate().ok());
    std::vector<Frame> first;
    run_sensor_recording(*s, c, first);
    for (std::size_t i = 0; i < first.size(); ++i) {
        const auto& f = first[i];
        INFO("frame " << i << " (t = " << f.time << " s): " << (f.valid ? "valid" : "invalid, reason: " + f.reason));
        REQUIRE(f.values.size() == channels.size());
        if (f.valid) {
            for (double v : f.values) CHECK(std::isfinite(v));
        } else {
            CHECK_FALSE(f.reason.empty());
        }
        if (c.expect_all_valid) CHECK(f.valid);
    }

    // the same trial (same seed) again gives the same data: sensors are reproducible
    std::vector<Frame> second;
    run_sensor_recording(*s, c, second);
    REQUIRE(second.size() == first.size());
    for (std::size_t i = 0; i < first.size(); ++i)
        for (std::size_t k = 0; k < channels.size(); ++k) {
            INFO("frame " << i << ", channel " << channels[k].name << ": the same trial again");
            if (first[i].valid && second[i].valid) CHECK(second[i].values[k] == Approx(first[i].values[k]).margin(1e-9));
        }

    // deactivate → cleanup → configure again: the lifecycle can be re-entered
    REQUIRE(s->on_deactivate().ok());
    REQUIRE(s->on_cleanup().ok());
    REQUIRE(s->on_configure(c.params, c.context).ok());
    CHECK(s->channels().size() == channels.size());
    REQUIRE(s->on_activate().ok());
    REQUIRE(s->on_deactivate().ok());
    REQUIRE(s->on_cleanup().ok());

    // unknown verbs are refused, not ignored
    auto r = s->invoke("no-such-verb-for-conformance", {});
    CHECK_FALSE(r.ok());
}

// ---------------------------------------------------------------- actuator --

struct ActuatorConformance {
    std::function<std::unique_ptr<Actuator>()> make;
    ParamSet params;
    PluginContext context;
    // The run clock and a way to let it pass: a virtual clock for models, a real
    // sleep for devices behind a pty or socket.
    std::function<double()> now;
    std::function<void(double seconds)> advance;
    double control_period = 0.01;
    double position_tolerance = 0.5;  // in the joint's unit
    double move_timeout = 10.0;       // seconds of run time for a small move
    double move_fraction = 0.1;       // size of the test move, as a fraction of the joint's range
};

inline std::vector<JointState> read_joints(Actuator& a, const ActuatorConformance& c, std::size_t n) {
    std::vector<JointState> s(n);
    auto st = a.read(c.now(), s);
    INFO("read: " << st.message());
    REQUIRE(st.ok());
    return s;
}

inline void check_actuator_conformance(const ActuatorConformance& c) {
    REQUIRE(c.make);
    REQUIRE(c.now);
    REQUIRE(c.advance);
    auto a = c.make();
    REQUIRE(a);
    {
        auto st = a->on_configure(c.params, c.context);
        INFO("on_configure: " << st.message());
        REQUIRE(st.ok());
    }
    const auto joints = a->joints();
    REQUIRE_FALSE(joints.empty());
    std::set<std::string> names;
    for (const auto& j : joints) {
        CHECK_FALSE(j.name.empty());
        CHECK(names.insert(j.name).second);
        CHECK(j.min_position < j.max_position);
        CHECK((j.unit == "deg" || j.unit == "mm"));
        CHECK_FALSE(j.modes.empty());
    }
    const std::size_t n = joints.size();

    {
        auto st = a->on_activate();
        INFO("on_activate: " << st.message());
        REQUIRE(st.ok());
    }

    // No jump on activation: holding what it reads keeps every joint where it is.
    auto start = read_joints(*a, c, n);
    std::vector<JointCommand> hold(n);
    for (std::size_t i = 0; i < n; ++i) {
        hold[i].mode = joints[i].modes.front() == ControlMode::current ? ControlMode::position : joints[i].modes.front();
        hold[i].position = start[i].position;
    }
    for (double t = 0; t < 0.3; t += c.control_period) {
        REQUIRE(a->write(c.now(), hold).ok());
        c.advance(c.control_period);
    }
    auto held = read_joints(*a, c, n);
    for (std::size_t i = 0; i < n; ++i) {
        INFO("joint " << joints[i].name);
        CHECK(held[i].position == Approx(start[i].position).margin(c.position_tolerance));
        CHECK(held[i].fault.empty());
    }

    // A small position move inside the limits arrives and reports not moving.
    std::vector<JointCommand> goal = hold;
    for (std::size_t i = 0; i < n; ++i) {
        const double range = joints[i].max_position - joints[i].min_position;
        double target = start[i].position + c.move_fraction * range;
        if (target > joints[i].max_position) target = start[i].position - c.move_fraction * range;
        goal[i].position = target;
    }
    double waited = 0;
    std::vector<JointState> now_state;
    for (;;) {
        REQUIRE(a->write(c.now(), goal).ok());
        c.advance(c.control_period);
        waited += c.control_period;
        now_state = read_joints(*a, c, n);
        bool arrived = true;
        for (std::size_t i = 0; i < n; ++i)
            arrived = arrived && !now_state[i].moving &&
                      std::abs(now_state[i].position - goal[i].position) <= c.position_tolerance;
        if (arrived || waited > c.move_timeout) break;
    }
    for (std::size_t i = 0; i < n; ++i) {
        INFO("joint " << joints[i].name << " goal " << goal[i].position);
        CHECK(now_state[i].position == Approx(goal[i].position).margin(c.position_tolerance));
        CHECK_FALSE(now_state[i].moving);
    }

    // Deactivate, cleanup, and the lifecycle can be re-entered.
    REQUIRE(a->on_deactivate().ok());
    REQUIRE(a->on_cleanup().ok());
    REQUIRE(a->on_configure(c.params, c.context).ok());
    REQUIRE(a->on_activate().ok());
    // Re-activation after a move holds the new position (no jump back to a stale goal).
    auto again = read_joints(*a, c, n);
    for (std::size_t i = 0; i < n; ++i)
        CHECK(again[i].position == Approx(now_state[i].position).margin(c.position_tolerance));
    REQUIRE(a->on_deactivate().ok());
    REQUIRE(a->on_cleanup().ok());
    CHECK_FALSE(a->invoke("no-such-verb-for-conformance", {}).ok());
}

}  // namespace rollsense::testing
