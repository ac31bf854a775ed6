#include "rollsense/hal/pty_pair.hpp"

#include <fcntl.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace rollsense::hal {

Status make_raw(int fd, const std::string& name) {
    termios tio{};
    if (tcgetattr(fd, &tio) != 0) {  // a file or /dev/null where a port was meant: the profile's mistake (exit 3)
        const int err = errno;
        return {err == ENOTTY ? ErrorCode::not_found : ErrorCode::io_error,
                name + ": not a terminal (tcgetattr: " + std::strerror(err) +
                    "); name the adapter's serial port (ls /dev/serial/by-id/, rollsense dxl scan)"};
    }
    cfmakeraw(&tio);
    tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS | CSIZE);
    tio.c_cflag |= CS8 | CLOCAL | CREAD;
    tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    // VMIN=0/VTIME=0: read() never blocks; poll() provides the timeouts.
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    if (tcsetattr(fd, TCSANOW, &tio) != 0)
        return {ErrorCode::io_error, name + ": cannot set raw mode (tcsetattr: " + std::strerror(errno) + ")"};
    return {};
}

Result<PtyPair> PtyPair::open() {
    PtyPair pair;
    pair.master_ = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (pair.master_ < 0)
        return Error{ErrorCode::io_error, std::string("cannot open a pseudo-terminal (posix_openpt: ") +
                                              std::strerror(errno) + "); is /dev/pts mounted?"};
    if (grantpt(pair.master_) != 0 || unlockpt(pair.master_) != 0)
        return Error{ErrorCode::io_error, std::string("cannot unlock the pseudo-terminal: ") + std::strerror(errno)};
    char name[128];
    if (ptsname_r(pair.master_, name, sizeof name) != 0)
        return Error{ErrorCode::io_error, std::string("ptsname failed: ") + std::strerror(errno)};
    pair.slave_path_ = name;
    pair.slave_keepalive_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (pair.slave_keepalive_ < 0)
        return Error{ErrorCode::io_error, pair.slave_path_ + ": cannot open pty slave: " + std::strerror(errno)};
    if (auto st = make_raw(pair.slave_keepalive_, pair.slave_path_); !st.ok()) return st;
    if (auto st = make_raw(pair.master_, "pty master"); !st.ok()) return st;
    const int flags = fcntl(pair.master_, F_GETFL);
    fcntl(pair.master_, F_SETFL, flags | O_NONBLOCK);
    return pair;
}

PtyPair::~PtyPair() { close(); }

PtyPair::PtyPair(PtyPair&& other) noexcept
    : master_(std::exchange(other.master_, -1)),
      slave_keepalive_(std::exchange(other.slave_keepalive_, -1)),
      slave_path_(std::move(other.slave_path_)) {}

PtyPair& PtyPair::operator=(PtyPair&& other) noexcept {
    if (this != &other) {
        close();
        master_ = std::exchange(other.master_, -1);
        slave_keepalive_ = std::exchange(other.slave_keepalive_, -1);
        slave_path_ = std::move(other.slave_path_);
    }
    return *this;
}

void PtyPair::close() noexcept {
    if (slave_keepalive_ >= 0) ::close(slave_keepalive_);
    if (master_ >= 0) ::close(master_);
    slave_keepalive_ = master_ = -1;
}

}  // namespace rollsense::hal
