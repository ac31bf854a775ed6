#include "mock_servo.hpp"

#include <algorithm>

namespace rollsense::mock {
namespace {
// Every control period writes every joint's command, almost always unchanged:
// local to this file, so the compiler inlines the test into command().
bool same(const JointCommand& a, const JointCommand& b) {
    return a.mode == b.mode && a.position == b.position && a.velocity == b.velocity && a.current == b.current &&
           a.profile_velocity == b.profile_velocity && a.profile_acceleration == b.profile_acceleration &&
           a.torque_enabled == b.torque_enabled;
}
}  // namespace

MockServo::MockServo(ServoModel model, double initial_position) : model_(model) {
    profile_.stop(0.0, std::clamp(initial_position, model_.min_position, model_.max_position));
    p0_ = profile_.goal();
    last_.position = p0_;
}

double MockServo::current_mode_position(double since_command) const {
    const double dir = last_.current > 0 ? 1.0 : (last_.current < 0 ? -1.0 : 0.0);
    double stop = dir > 0 ? model_.max_position : model_.min_position;
    if (!std::isnan(model_.contact) && (dir > 0 ? model_.contact >= p0_ : model_.contact <= p0_)) stop = model_.contact;
    const double speed = std::abs(last_.current) * model_.free_speed_per_ma;
    const double p = p0_ + dir * speed * since_command;
    return dir > 0 ? std::min(p, stop) : std::max(p, stop);
}

JointState MockServo::state(double t) const {
    JointState s;
    state(t, s);
    return s;
}

void MockServo::state(double t, JointState& s) const {
    s.mode = last_.mode;
    s.torque_enabled = torque_;
    if (s.fault != fault_) s.fault = fault_;
    s.fault_bits = fault_.empty() ? 0u : 1u;
    s.velocity = s.current = 0.0;
    s.moving = false;
    if (!torque_) {
        s.position = p0_;
        return;
    }
    switch (last_.mode) {
        case ControlMode::position:
        case ControlMode::extended_position:
        case ControlMode::current_based_position: {
            auto m = profile_.at(t);
            s.position = m.position;
            s.velocity = m.velocity;
            s.moving = m.moving;
            s.current = m.moving ? model_.moving_current : 0.0;
            break;
        }
        case ControlMode::current: {
            // From the time since the command (exact on the clock's grid), not
            // from t - 1e-3, which rounds differently at different clock magnitudes.
            s.position = current_mode_position(t - t0_);
            const double previous = current_mode_position(t - t0_ - 1e-3);
            s.velocity = (s.position - previous) / 1e-3;
            s.moving = std::abs(s.velocity) > 1e-9;
            // Against the contact the full commanded current flows; moving freely little does.
            s.current = s.moving ? 0.1 * last_.current : last_.current;
            break;
        }
        case ControlMode::velocity: {
            s.position = std::clamp(p0_ + last_.velocity * (t - t0_), model_.min_position, model_.max_position);
            s.velocity = (s.position == model_.min_position || s.position == model_.max_position) ? 0 : last_.velocity;
            s.moving = s.velocity != 0;
            break;
        }
    }
}

void MockServo::command(double t, const JointCommand& c) {
    if (has_command_ && same(c, last_)) return;
    const JointState now = state(t);
    has_command_ = true;
    last_ = c;
    if (!fault_.empty()) {  // a faulted servo keeps torque off until the fault is cleared (REBOOT)
        torque_ = false;
        p0_ = now.position;
        return;
    }
    torque_ = c.torque_enabled;
    p0_ = now.position;
    t0_ = t;
    if (!torque_) {
        profile_.stop(t, now.position);
        return;
    }
    switch (c.mode) {
        case ControlMode::position:
        case ControlMode::extended_position:
        case ControlMode::current_based_position: {
            const double goal = std::clamp(c.position, model_.min_position, model_.max_position);
            profile_.plan(t, now.position, now.velocity, goal, c.profile_velocity, c.profile_acceleration);
            break;
        }
        case ControlMode::current:
        case ControlMode::velocity: profile_.stop(t, now.position); break;
    }
}

void MockServo::inject_fault(double t, const std::string& fault) {
    const JointState now = state(t);
    fault_ = fault;
    torque_ = false;
    p0_ = now.position;
    profile_.stop(t, now.position);
}

void MockServo::clear_fault(double t) {
    const JointState now = state(t);
    fault_.clear();
    has_command_ = false;
    p0_ = now.position;
    profile_.stop(t, now.position);
}

}  // namespace rollsense::mock
