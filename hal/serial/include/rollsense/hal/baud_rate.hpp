// Baud-rate helpers shared by the serial backend and anything that computes
// bus timing.
#pragma once

#include <cstdint>
#include <optional>

#include "rollsense/status.hpp"

namespace rollsense::hal {

// The termios speed code (B9600, B57600, ...) for a standard rate, or nullopt
// when the rate has no code and must be set with termios2/BOTHER.
std::optional<unsigned> standard_speed_code(std::uint32_t baud) noexcept;

// Set an arbitrary rate on an open tty with termios2 (BOTHER). Used for rates
// without a classic speed code.
Status set_custom_baud(int fd, std::uint32_t baud);

// Read back the output rate the kernel actually applied (termios2), for
// checking that a custom rate took effect.
Result<std::uint32_t> query_baud(int fd);

}  // namespace rollsense::hal
