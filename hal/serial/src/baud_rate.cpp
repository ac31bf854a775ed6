#include <termios.h>

#include "rollsense/hal/baud_rate.hpp"

namespace rollsense::hal {

std::optional<unsigned> standard_speed_code(std::uint32_t baud) noexcept {
    switch (baud) {
        case 1200: return B1200;
        case 2400: return B2400;
        case 4800: return B4800;
        case 9600: return B9600;
        case 19200: return B19200;
        case 38400: return B38400;
        case 57600: return B57600;
        case 115200: return B115200;
        case 230400: return B230400;
        case 460800: return B460800;
        case 500000: return B500000;
        case 576000: return B576000;
        case 921600: return B921600;
        case 1000000: return B1000000;
        case 1152000: return B1152000;
        case 1500000: return B1500000;
        case 2000000: return B2000000;
        case 2500000: return B2500000;
        case 3000000: return B3000000;
        case 3500000: return B3500000;
        case 4000000: return B4000000;
        default: return std::nullopt;  // e.g. 4500000 (XM430 baud index 7)
    }
}

}  // namespace rollsense::hal
