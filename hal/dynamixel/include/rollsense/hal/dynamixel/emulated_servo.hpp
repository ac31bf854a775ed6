// One emulated X-series servo: its control table with the firmware's access
// and range rules, and a motion model (profile-following position modes,
// velocity mode, current mode pushing against a modelled contact).
//
// Emulation choices, kept deliberately strict so a client bug shows up here
// rather than on the hand:
// - Enabling torque does NOT reset Goal Position to the present position, so a
//   client that enables torque with a stale goal sees the servo jump.
// - A hardware error clears Torque Enable; only REBOOT clears the error, and
//   enabling torque while it is set answers "result fail".
// - Values outside an item's own range answer "data range error"; values
//   outside a limit set in another item (position, current, velocity limits)
//   answer "data limit error". A rejected write changes nothing.
// - Bus Watchdog (98): armed (1-127, x 20 ms) with torque on, it trips when no
//   instruction packet reached the servo for that long: the item reads -1,
//   the servo stops (velocity/current/PWM goals to zero, a position mode holds
//   where it is; torque stays on) and the goal items refuse writes (access
//   error) until 0 is written to 98. The e-manual shows only velocity mode;
//   the rest is our assumption, written down in docs/dynamixel.md.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "rollsense/hal/dynamixel/control_table.hpp"
#include "rollsense/hal/dynamixel/protocol.hpp"

namespace rollsense::hal::dxl {

struct ServoSetup {
    std::uint8_t id = 1;
    const ModelInfo* model = nullptr;  // nullptr = XM430-W350
    double start_degrees = 0.0;        // servo angle at power-up (0 = centre tick 2048)
    OperatingMode mode = OperatingMode::position;
    // A rigid obstacle (the object being clamped) at this servo angle; the
    // servo cannot move through it and pushes against it with its current.
    std::optional<double> contact_degrees;
    std::uint8_t baud_index = 1;  // 57600, the factory default
    std::uint8_t return_delay = 250;  // Return Delay Time, 2 µs units: 500 µs, the factory default
};

class EmulatedServo {
public:
    explicit EmulatedServo(const ServoSetup& setup);

    std::uint8_t id() const { return table_[addr::id]; }
    const ModelInfo& model() const { return *model_; }

    // Protocol access. Return the status ERR code (0 = success).
    std::uint8_t read(std::uint16_t address, std::uint16_t length, Bytes& out) const;
    std::uint8_t write(std::uint16_t address, std::span<const std::uint8_t> data);
    void reboot();

    // An instruction packet reached this servo (addressed to it or broadcast):
    // the Bus Watchdog starts counting again.
    void heard_instruction() { since_instruction_ = 0.0; }
    bool watchdog_tripped() const { return static_cast<std::int8_t>(table_[addr::bus_watchdog]) == -1; }
    // How often it tripped since power-up (for tests: a cleared trip leaves no other trace).
    int watchdog_trips() const { return watchdog_trips_; }

    // Advance the motion model by `seconds`.
    void step(double seconds);

    // ERR bit 7 in every status packet while a hardware error is latched.
    std::uint8_t alert_bits() const { return hardware_error() ? kAlertBit : 0; }
    std::uint8_t hardware_error() const { return table_[addr::hardware_error_status]; }
    // Fault injection: latch hardware error bits (torque goes off).
    void raise_hardware_error(std::uint8_t bits);

    void set_contact(std::optional<double> contact_degrees);
    // An obstacle at `contact_degrees` blocking motion toward higher angles
    // (side +1) or lower ones (side -1); one that moves into the servo's
    // position pushes the horn back with it.
    void set_obstacle(double contact_degrees, double side);
    // Direct inspection (tests, the emulator's status line).
    std::int32_t item(std::uint16_t address, std::uint16_t size) const;
    double position_ticks() const { return position_; }
    double velocity_ticks_s() const { return velocity_; }
    double current_ma() const { return current_ma_; }
    bool torque_enabled() const { return table_[addr::torque_enable] != 0; }
    OperatingMode mode() const { return static_cast<OperatingMode>(table_[addr::operating_mode]); }

private:
    using Table = std::array<std::uint8_t, addr::table_size>;
    void init_table(double start_ticks);
    std::uint8_t validate(const Table& next, std::uint16_t first, std::uint16_t last) const;
    void substep(double dt);
    void publish();
    std::int32_t get(const Table& t, std::uint16_t address, std::uint16_t size) const;
    void set(std::uint16_t address, std::uint16_t size, std::int64_t value);
    // Where motion toward `target` (ticks) stops: the target, or the contact in between.
    double reachable(double target) const;
    bool blocked_toward(double direction) const;

    const ModelInfo* model_;
    Table table_{};
    double position_ = kCentreTick;  // ticks
    double velocity_ = 0.0;          // ticks/s
    double current_ma_ = 0.0;
    double clock_ = 0.0;
    double since_instruction_ = 0.0;  // s, for the Bus Watchdog
    int watchdog_trips_ = 0;
    void trip_watchdog();
    bool profile_running_ = false;
    std::optional<double> contact_ticks_;
    double contact_side_ = 1.0;  // +1: the obstacle blocks motion toward higher ticks
};

}  // namespace rollsense::hal::dxl
