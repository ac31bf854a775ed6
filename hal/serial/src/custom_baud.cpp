// termios2 lives in <asm/termbits.h>, whose struct termios clashes with glibc's
// <termios.h>; this file therefore includes only the kernel header and declares
// ioctl() itself.
#include <asm/ioctls.h>
#include <asm/termbits.h>
#include <cerrno>
#include <cstring>
#include <string>

#include "rollsense/hal/baud_rate.hpp"

extern "C" int ioctl(int fd, unsigned long request, ...);

namespace rollsense::hal {

Status set_custom_baud(int fd, std::uint32_t baud) {
    struct termios2 tio {};
    if (ioctl(fd, TCGETS2, &tio) != 0)
        return {ErrorCode::io_error, std::string("TCGETS2 failed: ") + std::strerror(errno)};
    tio.c_cflag &= ~static_cast<tcflag_t>(CBAUD);
    tio.c_cflag |= BOTHER;
    tio.c_ispeed = baud;
    tio.c_ospeed = baud;
    // The input rate follows the output rate unless IBSHIFT bits say otherwise.
    tio.c_cflag &= ~static_cast<tcflag_t>(CBAUD << IBSHIFT);
    tio.c_cflag |= static_cast<tcflag_t>(BOTHER << IBSHIFT);
    if (ioctl(fd, TCSETS2, &tio) != 0)
        return {ErrorCode::io_error, "cannot set custom baud rate " + std::to_string(baud) +
                                         " (TCSETS2: " + std::strerror(errno) +
                                         "); the adapter's driver may not support arbitrary rates"};
    return {};
}

Result<std::uint32_t> query_baud(int fd) {
    struct termios2 tio {};
    if (ioctl(fd, TCGETS2, &tio) != 0)
        return Error{ErrorCode::io_error, std::string("TCGETS2 failed: ") + std::strerror(errno)};
    return static_cast<std::uint32_t>(tio.c_ospeed);
}

}  // namespace rollsense::hal
