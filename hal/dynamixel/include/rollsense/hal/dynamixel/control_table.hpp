// X-series control table (XM430-W350 and XL330-M288 share the addresses) and
// per-model units. Facts: docs/hardware.md §4.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rollsense::hal::dxl {

namespace addr {
inline constexpr std::uint16_t model_number = 0;       // 2, RO
inline constexpr std::uint16_t model_information = 2;  // 4, RO
inline constexpr std::uint16_t firmware_version = 6;   // 1, RO
inline constexpr std::uint16_t id = 7;                 // 1, EEPROM
inline constexpr std::uint16_t baud_rate = 8;          // 1, EEPROM
inline constexpr std::uint16_t return_delay_time = 9;  // 1, EEPROM, 2 us/unit
inline constexpr std::uint16_t drive_mode = 10;        // 1, EEPROM
inline constexpr std::uint16_t operating_mode = 11;    // 1, EEPROM
inline constexpr std::uint16_t homing_offset = 20;     // 4, EEPROM
inline constexpr std::uint16_t moving_threshold = 24;  // 4, EEPROM
inline constexpr std::uint16_t temperature_limit = 31; // 1, EEPROM
inline constexpr std::uint16_t max_voltage_limit = 32; // 2, EEPROM
inline constexpr std::uint16_t min_voltage_limit = 34; // 2, EEPROM
inline constexpr std::uint16_t pwm_limit = 36;         // 2, EEPROM
inline constexpr std::uint16_t current_limit = 38;     // 2, EEPROM
inline constexpr std::uint16_t velocity_limit = 44;    // 4, EEPROM
inline constexpr std::uint16_t max_position_limit = 48;// 4, EEPROM
inline constexpr std::uint16_t min_position_limit = 52;// 4, EEPROM
inline constexpr std::uint16_t shutdown = 63;          // 1, EEPROM
inline constexpr std::uint16_t torque_enable = 64;     // 1
inline constexpr std::uint16_t led = 65;               // 1
inline constexpr std::uint16_t status_return_level = 68;
inline constexpr std::uint16_t registered_instruction = 69;  // RO
inline constexpr std::uint16_t hardware_error_status = 70;   // RO
inline constexpr std::uint16_t bus_watchdog = 98;      // 1, signed: 0 off, 1-127 x 20 ms, -1 tripped
inline constexpr std::uint16_t goal_pwm = 100;         // 2
inline constexpr std::uint16_t goal_current = 102;     // 2, signed
inline constexpr std::uint16_t goal_velocity = 104;    // 4, signed
inline constexpr std::uint16_t profile_acceleration = 108;  // 4
inline constexpr std::uint16_t profile_velocity = 112;      // 4
inline constexpr std::uint16_t goal_position = 116;    // 4, signed
inline constexpr std::uint16_t realtime_tick = 120;    // 2, RO
inline constexpr std::uint16_t moving = 122;           // 1, RO
inline constexpr std::uint16_t moving_status = 123;    // 1, RO
inline constexpr std::uint16_t present_pwm = 124;      // 2, RO
inline constexpr std::uint16_t present_current = 126;  // 2, RO, signed
inline constexpr std::uint16_t present_velocity = 128; // 4, RO, signed
inline constexpr std::uint16_t present_position = 132; // 4, RO, signed
inline constexpr std::uint16_t velocity_trajectory = 136;  // 4, RO
inline constexpr std::uint16_t position_trajectory = 140;  // 4, RO
inline constexpr std::uint16_t present_input_voltage = 144;// 2, RO, 0.1 V
inline constexpr std::uint16_t present_temperature = 146;  // 1, RO, degC
inline constexpr std::uint16_t table_size = 147;       // what the emulator models
}  // namespace addr

// The block one control period writes for every servo with one SYNC_WRITE:
// Goal Current .. Goal Position (102..119), contiguous on the X series.
inline constexpr std::uint16_t kCommandBlockAddress = addr::goal_current;
inline constexpr std::uint16_t kCommandBlockLength = 18;
// The block one control period reads with one SYNC_READ: Moving .. Present
// Position (122..135).
inline constexpr std::uint16_t kStateBlockAddress = addr::moving;
inline constexpr std::uint16_t kStateBlockLength = 14;

// Operating Mode (address 11) values.
enum class OperatingMode : std::uint8_t {
    current = 0,
    velocity = 1,
    position = 3,
    extended_position = 4,
    current_based_position = 5,
    pwm = 16,
};
std::string to_string(OperatingMode mode);
bool is_valid_operating_mode(std::uint8_t value);

// Units and limits of one servo model.
struct ModelInfo {
    std::string_view name;
    std::uint16_t model_number;
    double current_unit_ma;           // Goal/Present Current, Current Limit
    std::uint16_t max_current_limit;  // largest Current Limit value
    std::uint32_t default_velocity_limit;  // factory Velocity Limit (units of 0.229 rev/min)
    std::uint8_t max_baud_index;      // 7 = 4.5 Mbps (XM430 only), 6 = 4 Mbps
    double default_input_voltage;     // V, what the emulator reports
};

inline constexpr double kTicksPerRevolution = 4096.0;
inline constexpr std::int32_t kCentreTick = 2048;
inline constexpr double kVelocityUnitRpm = 0.229;        // rev/min per unit
inline constexpr double kAccelerationUnitRpm2 = 214.577; // rev/min^2 per unit
inline constexpr std::int32_t kExtendedPositionLimit = 1'048'575;  // +-256 turns

// Every model this project knows. nullptr / nullopt when unknown.
const std::vector<ModelInfo>& known_models();
const ModelInfo* find_model(std::string_view name);
const ModelInfo* find_model(std::uint16_t model_number);

// Baud Rate (address 8) index <-> bits/s.
std::optional<std::uint32_t> baud_from_index(std::uint8_t index);
std::optional<std::uint8_t> index_from_baud(std::uint32_t baud);

// ---- unit conversions (servo side; joint scaling and offsets live in the plugin)
// Servo angle in degrees, 0 deg at the centre tick 2048.
double ticks_to_degrees(double ticks);
std::int32_t degrees_to_ticks(double degrees);
// Velocity units (0.229 rev/min) <-> degrees per second.
double velocity_units_to_deg_s(double units);
double deg_s_to_velocity_units(double deg_s);
double velocity_units_to_rpm(double units);
double rpm_to_velocity_units(double rpm);
// Acceleration units (214.577 rev/min^2) <-> degrees per second^2.
double acceleration_units_to_deg_s2(double units);
double deg_s2_to_acceleration_units(double deg_s2);
// Current units <-> mA, per model.
double current_units_to_ma(const ModelInfo& model, double units);
double ma_to_current_units(const ModelInfo& model, double ma);

}  // namespace rollsense::hal::dxl
