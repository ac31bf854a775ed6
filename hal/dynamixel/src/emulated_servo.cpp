#include "rollsense/hal/dynamixel/emulated_servo.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rollsense::hal::dxl {
namespace {

// Velocity unit (0.229 rev/min) in ticks per second.
constexpr double kTicksPerSecondPerVelocityUnit = kVelocityUnitRpm / 60.0 * kTicksPerRevolution;
// Acceleration unit (214.577 rev/min^2) in ticks per second^2.
constexpr double kTicksPerSecond2PerAccelUnit = kAccelerationUnitRpm2 / 3600.0 * kTicksPerRevolution;
constexpr double kSubstep = 0.001;  // seconds: the model integrates at 1 kHz
constexpr double kFreeRunCurrentFraction = 0.1;  // of Current Limit: unloaded current mode at full speed

constexpr auto E_RANGE = static_cast<std::uint8_t>(StatusError::data_range);
constexpr auto E_LIMIT = static_cast<std::uint8_t>(StatusError::data_limit);
constexpr auto E_ACCESS = static_cast<std::uint8_t>(StatusError::access);
constexpr auto E_FAIL = static_cast<std::uint8_t>(StatusError::result_fail);

bool read_only(std::uint16_t a) { return a < 7 || a == 69 || a == 70 || a >= 120; }
bool overlaps(std::uint16_t first, std::uint16_t last, std::uint16_t item, std::uint16_t size) {
    return first < item + size && item <= last;
}

}  // namespace

EmulatedServo::EmulatedServo(const ServoSetup& setup)
    : model_(setup.model ? setup.model : find_model("XM430-W350")) {
    const double start = kCentreTick + setup.start_degrees * kTicksPerRevolution / 360.0;
    init_table(start);
    table_[addr::id] = setup.id;
    table_[addr::operating_mode] = static_cast<std::uint8_t>(setup.mode);
    table_[addr::baud_rate] = setup.baud_index;
    table_[addr::return_delay_time] = setup.return_delay;
    position_ = start;
    set_contact(setup.contact_degrees);
    publish();
}

void EmulatedServo::init_table(double start_ticks) {
    table_.fill(0);
    const bool xl = model_->model_number == 1200;
    set(addr::model_number, 2, model_->model_number);
    set(addr::firmware_version, 1, 48);
    set(addr::id, 1, 1);
    set(addr::baud_rate, 1, 1);
    set(addr::return_delay_time, 1, 250);
    set(addr::operating_mode, 1, static_cast<int>(OperatingMode::position));
    set(addr::moving_threshold, 4, 10);
    set(addr::temperature_limit, 1, xl ? 70 : 80);
    set(addr::max_voltage_limit, 2, xl ? 70 : 160);
    set(addr::min_voltage_limit, 2, xl ? 35 : 95);
    set(addr::pwm_limit, 2, 885);
    set(addr::current_limit, 2, model_->max_current_limit);
    set(addr::velocity_limit, 4, model_->default_velocity_limit);
    set(addr::max_position_limit, 4, 4095);
    set(addr::min_position_limit, 4, 0);
    set(addr::shutdown, 1, hw_error::overheating | hw_error::electrical_shock | hw_error::overload);
    set(addr::status_return_level, 1, 2);
    set(addr::goal_pwm, 2, 885);
    set(addr::goal_current, 2, model_->max_current_limit);
    set(addr::goal_position, 4, std::lround(start_ticks));
    set(addr::present_input_voltage, 2, std::lround(model_->default_input_voltage * 10));
    set(addr::present_temperature, 1, 31);
}

std::int32_t EmulatedServo::get(const Table& t, std::uint16_t address, std::uint16_t size) const {
    return get_le_signed(&t[address], size);
}

void EmulatedServo::set(std::uint16_t address, std::uint16_t size, std::int64_t value) {
    Bytes b;
    put_le(b, value, size);
    std::copy(b.begin(), b.end(), table_.begin() + address);
}

std::int32_t EmulatedServo::item(std::uint16_t address, std::uint16_t size) const {
    return get(table_, address, size);
}

void EmulatedServo::set_contact(std::optional<double> contact_degrees) {
    if (contact_degrees) {
        const double ticks = kCentreTick + *contact_degrees * kTicksPerRevolution / 360.0;
        // The obstacle is on the side the servo would have to move toward to reach it.
        set_obstacle(*contact_degrees, ticks >= position_ ? 1.0 : -1.0);
    } else {
        contact_ticks_.reset();
    }
}

void EmulatedServo::set_obstacle(double contact_degrees, double side) {
    const double ticks = kCentreTick + contact_degrees * kTicksPerRevolution / 360.0;
    contact_ticks_ = ticks;
    contact_side_ = side >= 0 ? 1.0 : -1.0;
    // An obstacle that moved into the horn pushes it back (the object is
    // driven by the other fingers, which are stiffer than this one's torque).
    if ((contact_side_ > 0 && position_ > ticks) || (contact_side_ < 0 && position_ < ticks)) {
        position_ = ticks;
        if (velocity_ * contact_side_ > 0) velocity_ = 0.0;
    }
}

std::uint8_t EmulatedServo::read(std::uint16_t address, std::uint16_t length, Bytes& out) const {
    if (length == 0 || address + length > addr::table_size) return E_RANGE;
    out.assign(table_.begin() + address, table_.begin() + address + length);
    return 0;
}

std::uint8_t EmulatedServo::validate(const Table& next, std::uint16_t first, std::uint16_t last) const {
    auto touched = [&](std::uint16_t a, std::uint16_t s) { return overlaps(first, last, a, s); };
    auto value = [&](std::uint16_t a, std::uint16_t s) { return get(next, a, s); };
    auto uvalue = [&](std::uint16_t a, std::uint16_t s) { return get_le(&next[a], s); };
    if (touched(addr::id, 1) && uvalue(addr::id, 1) > kMaxId) return E_RANGE;
    if (touched(addr::baud_rate, 1) && uvalue(addr::baud_rate, 1) > model_->max_baud_index) return E_RANGE;
    if (touched(addr::operating_mode, 1) &&
        !is_valid_operating_mode(static_cast<std::uint8_t>(uvalue(addr::operating_mode, 1))))
        return E_RANGE;
    if (touched(addr::current_limit, 2) && uvalue(addr::current_limit, 2) > model_->max_current_limit) return E_RANGE;
    if (touched(addr::velocity_limit, 4) && uvalue(addr::velocity_limit, 4) > 2047) return E_RANGE;
    for (auto a : {addr::max_position_limit, addr::min_position_limit})
        if (touched(a, 4) && uvalue(a, 4) > 4095) return E_RANGE;
    if (touched(addr::torque_enable, 1) && uvalue(addr::torque_enable, 1) > 1) return E_RANGE;
    if (touched(addr::bus_watchdog, 1) && uvalue(addr::bus_watchdog, 1) > 127) return E_RANGE;
    if (touched(addr::goal_current, 2) && std::abs(value(addr::goal_current, 2)) > value(addr::current_limit, 2))
        return E_LIMIT;
    if (touched(addr::goal_velocity, 4) &&
        std::abs(value(addr::goal_velocity, 4)) > value(addr::velocity_limit, 4))
        return E_LIMIT;
    for (auto a : {addr::profile_acceleration, addr::profile_velocity})
        if (touched(a, 4) && uvalue(a, 4) > 32767) return E_RANGE;
    if (touched(addr::goal_position, 4)) {
        const auto goal = value(addr::goal_position, 4);
        const auto mode = static_cast<OperatingMode>(next[addr::operating_mode]);
        if (mode == OperatingMode::position) {
            if (goal < value(addr::min_position_limit, 4) || goal > value(addr::max_position_limit, 4))
                return E_LIMIT;
        } else if (std::abs(goal) > kExtendedPositionLimit) {
            return E_RANGE;
        }
    }
    return 0;
}

std::uint8_t EmulatedServo::write(std::uint16_t address, std::span<const std::uint8_t> data) {
    if (data.empty() || address + data.size() > addr::table_size) return E_RANGE;
    const auto first = address;
    const auto last = static_cast<std::uint16_t>(address + data.size() - 1);
    for (std::uint16_t a = first; a <= last; ++a) {
        if (read_only(a)) return E_ACCESS;
        if (a < addr::torque_enable && torque_enabled()) return E_ACCESS;  // EEPROM needs torque off
        // A tripped Bus Watchdog makes the goals read-only until 98 is cleared.
        if (watchdog_tripped() && a >= addr::goal_pwm && a < addr::goal_position + 4) return E_ACCESS;
    }
    Table next = table_;
    std::copy(data.begin(), data.end(), next.begin() + address);
    if (auto err = validate(next, first, last)) return err;
    const bool enabling = !torque_enabled() && next[addr::torque_enable] == 1;
    if (enabling && hardware_error()) return E_FAIL;
    const bool mode_changed = next[addr::operating_mode] != table_[addr::operating_mode];
    table_ = next;
    if (mode_changed) {
        // As the firmware does: a new mode starts from neutral profiles and full current.
        set(addr::profile_velocity, 4, 0);
        set(addr::profile_acceleration, 4, 0);
        set(addr::goal_current, 2, item(addr::current_limit, 2));
        set(addr::goal_pwm, 2, item(addr::pwm_limit, 2));
    }
    if (overlaps(first, last, addr::goal_position, 4) && torque_enabled()) profile_running_ = true;
    publish();
    return 0;
}

void EmulatedServo::reboot() {
    // EEPROM survives; RAM returns to power-up values.
    Table eeprom = table_;
    const double here = position_;
    init_table(here);
    std::copy(eeprom.begin() + 7, eeprom.begin() + addr::torque_enable, table_.begin() + 7);
    set(addr::goal_current, 2, item(addr::current_limit, 2));
    velocity_ = 0.0;
    current_ma_ = 0.0;
    profile_running_ = false;
    publish();
}

void EmulatedServo::raise_hardware_error(std::uint8_t bits) {
    table_[addr::hardware_error_status] |= bits;
    table_[addr::torque_enable] = 0;
    publish();
}

double EmulatedServo::reachable(double target) const {
    if (!contact_ticks_) return target;
    const double c = *contact_ticks_;
    if (contact_side_ > 0 && target > c) return c;
    if (contact_side_ < 0 && target < c) return c;
    return target;
}

bool EmulatedServo::blocked_toward(double direction) const {
    if (!contact_ticks_ || direction == 0.0) return false;
    return std::abs(position_ - *contact_ticks_) < 1e-6 && direction * contact_side_ > 0;
}

void EmulatedServo::trip_watchdog() {
    table_[addr::bus_watchdog] = 0xFF;  // -1
    ++watchdog_trips_;
    // "Stop", per mode (our assumption beyond the e-manual's velocity example).
    switch (mode()) {
        case OperatingMode::velocity: set(addr::goal_velocity, 4, 0); break;
        case OperatingMode::current: set(addr::goal_current, 2, 0); break;
        case OperatingMode::pwm: set(addr::goal_pwm, 2, 0); break;
        default:  // position modes: hold where it is now
            set(addr::goal_position, 4, std::lround(position_));
            break;
    }
}

void EmulatedServo::step(double seconds) {
    while (seconds > 1e-12) {
        const double dt = std::min(seconds, kSubstep);
        since_instruction_ += dt;
        const auto watchdog = static_cast<std::int8_t>(table_[addr::bus_watchdog]);
        if (watchdog > 0 && torque_enabled() && since_instruction_ > watchdog * 0.020) trip_watchdog();
        substep(dt);
        seconds -= dt;
        clock_ += dt;
    }
    publish();
}

void EmulatedServo::substep(double dt) {
    const double limit_ma = current_units_to_ma(*model_, item(addr::current_limit, 2));
    const double vlimit = item(addr::velocity_limit, 4) * kTicksPerSecondPerVelocityUnit;
    if (!torque_enabled()) {
        velocity_ = 0.0;
        current_ma_ = 0.0;
        profile_running_ = false;
        return;
    }
    const auto mode = this->mode();
    const double pa_units = item(addr::profile_acceleration, 4);
    const double accel = pa_units > 0 ? pa_units * kTicksPerSecond2PerAccelUnit
                                      : std::numeric_limits<double>::infinity();

    auto move_by = [&](double v) {
        const double next = position_ + v * dt;
        const double stop = reachable(next);
        position_ = stop;
        velocity_ = stop == next ? v : 0.0;
    };

    if (mode == OperatingMode::current || mode == OperatingMode::pwm) {
        const double goal_ma = current_units_to_ma(*model_, item(addr::goal_current, 2));
        const double dir = goal_ma > 0 ? 1.0 : goal_ma < 0 ? -1.0 : 0.0;
        if (blocked_toward(dir)) {
            velocity_ = 0.0;
            current_ma_ = goal_ma;  // pushing on the contact with the commanded torque
        } else {
            // Unloaded, speed grows with the commanded current and reaches the
            // velocity limit at a small fraction of the current limit (a
            // coreless motor with no load needs little torque to run at speed;
            // the fraction is a round emulation figure, not a datasheet value).
            // A clamping finger must keep up with an object that rolls away.
            const double free_run_ma = kFreeRunCurrentFraction * limit_ma;
            const double frac = free_run_ma > 0 ? std::min(1.0, std::abs(goal_ma) / free_run_ma) : 0.0;
            move_by(dir * vlimit * frac);
            current_ma_ = blocked_toward(dir) ? goal_ma : 0.1 * goal_ma;
        }
        profile_running_ = false;
        return;
    }

    if (mode == OperatingMode::velocity) {
        const double want = item(addr::goal_velocity, 4) * kTicksPerSecondPerVelocityUnit;
        const double dv = std::clamp(want - velocity_, -accel * dt, accel * dt);
        const double v = velocity_ + dv;
        const double dir = v > 0 ? 1.0 : v < 0 ? -1.0 : 0.0;
        if (blocked_toward(dir)) {
            velocity_ = 0.0;
            current_ma_ = dir * limit_ma;
        } else {
            move_by(v);
            current_ma_ = 0.03 * limit_ma * dir;
        }
        profile_running_ = false;
        return;
    }

    // Position modes: follow a trapezoidal profile toward the goal.
    const double goal = item(addr::goal_position, 4);
    const double pv_units = item(addr::profile_velocity, 4);
    double vmax = pv_units > 0 ? pv_units * kTicksPerSecondPerVelocityUnit : vlimit;
    if (vlimit > 0) vmax = std::min(vmax, vlimit);
    const double stop = reachable(goal);
    const double err = stop - position_;
    const double dir = goal > position_ ? 1.0 : goal < position_ ? -1.0 : 0.0;
    if (std::abs(err) < 0.5 && std::abs(velocity_) * dt < 0.5) {
        position_ = stop;
        velocity_ = 0.0;
    } else {
        const double sign = err > 0 ? 1.0 : -1.0;
        double want = sign * std::min({vmax, std::sqrt(2.0 * accel * std::abs(err)), std::abs(err) / dt});
        const double dv = std::clamp(want - velocity_, -accel * dt, accel * dt);
        double v = velocity_ + dv;
        double next = position_ + v * dt;
        if ((sign > 0 && next > stop) || (sign < 0 && next < stop)) {
            next = stop;
            v = 0.0;
        }
        velocity_ = v;
        position_ = next;
    }
    const bool at_contact = stop != goal && std::abs(position_ - stop) < 1e-6;
    if (at_contact) {
        const double ceiling = mode == OperatingMode::current_based_position
                                   ? std::abs(current_units_to_ma(*model_, item(addr::goal_current, 2)))
                                   : limit_ma;
        current_ma_ = dir * ceiling;
        velocity_ = 0.0;
    } else {
        current_ma_ = velocity_ == 0.0 ? 0.0 : 0.03 * limit_ma * (velocity_ > 0 ? 1.0 : -1.0);
    }
    profile_running_ = !at_contact && std::abs(goal - position_) >= 0.5;
}

void EmulatedServo::publish() {
    const double unit = model_->current_unit_ma;
    const auto vel_units = std::lround(velocity_ / kTicksPerSecondPerVelocityUnit);
    set(addr::present_position, 4, std::lround(position_));
    set(addr::present_velocity, 4, vel_units);
    set(addr::present_current, 2, std::lround(current_ma_ / unit));
    const bool moving = profile_running_ || std::abs(vel_units) > item(addr::moving_threshold, 4);
    table_[addr::moving] = moving ? 1 : 0;
    // Moving Status: bit0 in position, bit1 profile ongoing.
    table_[addr::moving_status] = static_cast<std::uint8_t>((profile_running_ ? 0x02 : 0x01));
    set(addr::realtime_tick, 2, std::lround(clock_ * 1000.0) % 32768);
    set(addr::position_trajectory, 4, item(addr::goal_position, 4));
}

}  // namespace rollsense::hal::dxl
