#include "rollsense/hal/dynamixel/control_table.hpp"

#include <cmath>

namespace rollsense::hal::dxl {

std::string to_string(OperatingMode mode) {
    switch (mode) {
        case OperatingMode::current: return "current";
        case OperatingMode::velocity: return "velocity";
        case OperatingMode::position: return "position";
        case OperatingMode::extended_position: return "extended position";
        case OperatingMode::current_based_position: return "current-based position";
        case OperatingMode::pwm: return "PWM";
    }
    return "mode " + std::to_string(static_cast<int>(mode));
}

bool is_valid_operating_mode(std::uint8_t v) { return v == 0 || v == 1 || v == 3 || v == 4 || v == 5 || v == 16; }

const std::vector<ModelInfo>& known_models() {
    // XM430-W350: 2.69 mA/unit, Current Limit up to 1193, Velocity Limit 200 (45.8 rev/min at 12 V).
    // XL330-M288: 1 mA/unit, Current Limit up to 1750, Velocity Limit 445 (~102 rev/min at 5 V).
    static const std::vector<ModelInfo> models{
        {"XM430-W350", 1020, 2.69, 1193, 200, 7, 12.0},
        {"XL330-M288", 1200, 1.0, 1750, 445, 6, 5.0},
    };
    return models;
}

const ModelInfo* find_model(std::string_view name) {
    for (const auto& m : known_models())
        if (m.name == name) return &m;
    return nullptr;
}

const ModelInfo* find_model(std::uint16_t model_number) {
    for (const auto& m : known_models())
        if (m.model_number == model_number) return &m;
    return nullptr;
}

std::optional<std::uint32_t> baud_from_index(std::uint8_t index) {
    static constexpr std::uint32_t rates[] = {9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000, 4500000};
    if (index >= std::size(rates)) return std::nullopt;
    return rates[index];
}

std::optional<std::uint8_t> index_from_baud(std::uint32_t baud) {
    for (std::uint8_t i = 0; i < 8; ++i)
        if (baud_from_index(i) == baud) return i;
    return std::nullopt;
}

double ticks_to_degrees(double ticks) { return (ticks - kCentreTick) * 360.0 / kTicksPerRevolution; }
std::int32_t degrees_to_ticks(double degrees) {
    return static_cast<std::int32_t>(std::lround(degrees * kTicksPerRevolution / 360.0)) + kCentreTick;
}
double velocity_units_to_rpm(double units) { return units * kVelocityUnitRpm; }
double rpm_to_velocity_units(double rpm) { return rpm / kVelocityUnitRpm; }
double velocity_units_to_deg_s(double units) { return velocity_units_to_rpm(units) * 360.0 / 60.0; }
double deg_s_to_velocity_units(double deg_s) { return rpm_to_velocity_units(deg_s * 60.0 / 360.0); }
double acceleration_units_to_deg_s2(double units) { return units * kAccelerationUnitRpm2 * 360.0 / 3600.0; }
double deg_s2_to_acceleration_units(double deg_s2) { return deg_s2 * 3600.0 / 360.0 / kAccelerationUnitRpm2; }
double current_units_to_ma(const ModelInfo& model, double units) { return units * model.current_unit_ma; }
double ma_to_current_units(const ModelInfo& model, double ma) { return ma / model.current_unit_ma; }

}  // namespace rollsense::hal::dxl
