#include "joint_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rollsense::dynamixel {

using namespace hal::dxl;

double JointMap::scale() const {
    if (unit == "mm") return ratio * radius_mm * std::numbers::pi / 180.0;
    return 1.0;
}

double JointMap::ticks_to_joint(double ticks) const { return ticks_to_degrees(ticks) * scale() + offset; }

std::int32_t JointMap::joint_to_ticks(double position) const {
    return degrees_to_ticks((position - offset) / scale());
}

double JointMap::velocity_units_to_joint(double units) const { return velocity_units_to_deg_s(units) * scale(); }

std::int32_t JointMap::joint_to_velocity_units(double velocity) const {
    return static_cast<std::int32_t>(std::lround(deg_s_to_velocity_units(velocity / scale())));
}

std::uint32_t JointMap::joint_to_profile_velocity(double velocity) const {
    // 0 is the servo's "no limit": never written. "The device's maximum" (0, or a negative or NaN that got
    // this far) is this joint's max_velocity, else the model's factory Velocity Limit.
    if (!(velocity > 0.0)) velocity = max_velocity;
    if (!(velocity > 0.0)) return model->default_velocity_limit;
    const double units = std::min(deg_s_to_velocity_units(velocity / scale()), 32767.0);  // lround(inf) is undefined
    return static_cast<std::uint32_t>(std::clamp(std::lround(units), 1L, 32767L));
}

std::uint32_t JointMap::joint_to_profile_acceleration(double acceleration) const {
    if (acceleration <= 0.0) return 0;
    const double units = deg_s2_to_acceleration_units(acceleration / scale());
    return static_cast<std::uint32_t>(std::clamp(std::lround(units), 1L, 32767L));
}

double JointMap::current_units_to_ma(double units) const { return hal::dxl::current_units_to_ma(*model, units); }

std::int32_t JointMap::ma_to_current_units(double ma) const {
    return static_cast<std::int32_t>(std::lround(hal::dxl::ma_to_current_units(*model, ma)));
}

std::uint16_t JointMap::current_limit_units() const {
    if (max_current_ma <= 0.0) return model->max_current_limit;
    // Down (hardware review: 400 mA became 149 units, 400.81 mA): the servo's limit never exceeds the profile's.
    const auto units = static_cast<long>(std::floor(hal::dxl::ma_to_current_units(*model, max_current_ma) + 1e-9));
    return static_cast<std::uint16_t>(std::clamp<long>(units, 1, model->max_current_limit));
}

OperatingMode to_operating_mode(ControlMode mode) {
    switch (mode) {
        case ControlMode::position: return OperatingMode::position;
        case ControlMode::extended_position: return OperatingMode::extended_position;
        case ControlMode::velocity: return OperatingMode::velocity;
        case ControlMode::current: return OperatingMode::current;
        case ControlMode::current_based_position: return OperatingMode::current_based_position;
    }
    return OperatingMode::position;
}

ControlMode to_control_mode(OperatingMode mode) {
    switch (mode) {
        case OperatingMode::extended_position: return ControlMode::extended_position;
        case OperatingMode::velocity: return ControlMode::velocity;
        case OperatingMode::current: return ControlMode::current;
        case OperatingMode::current_based_position: return ControlMode::current_based_position;
        default: return ControlMode::position;
    }
}

}  // namespace rollsense::dynamixel
