// Faults the emulator injects on a schedule, as `rollsense-dxl-emu --inject`
// and the dynamixel plugin's in-process emulator (`inject` parameter) take
// them: "ID:KIND:AFTER_S", the servo id, what goes wrong, and after how many
// seconds of emulated time (from the emulator's start).
//   silent          the servo stops answering (the client times out)
//   hardware-error  an overload: Hardware Error Status (70) set, the alert bit
//                   in every status packet, torque off (as the firmware does)
//   corrupt         every reply has a wrong CRC
//   slow            every reply comes kLateBy late (past any sane timeout)
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "rollsense/status.hpp"

namespace rollsense::hal::dxl {

enum class FaultKind { silent, hardware_error, corrupt, slow };

struct InjectedFault {
    std::uint8_t id = 1;
    FaultKind kind = FaultKind::silent;
    double after_s = 0;
};

// How late a `slow` servo answers: longer than every retry of the plugin's
// timeout (timeout_ms up to 100, 3 retries), so the client gives up.
inline constexpr std::chrono::milliseconds kLateBy{500};

std::string_view to_string(FaultKind kind);
// "2:silent:1.5" -> {2, silent, 1.5}; errors name the spec and the fix.
Result<InjectedFault> parse_injected_fault(std::string_view spec);

}  // namespace rollsense::hal::dxl
