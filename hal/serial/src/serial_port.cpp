#include "rollsense/hal/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include "rollsense/hal/baud_rate.hpp"
#include "rollsense/hal/pty_pair.hpp"

namespace rollsense::hal {
namespace {

using Clock = std::chrono::steady_clock;

std::string errno_text() { return std::strerror(errno); }

int poll_ms(std::chrono::microseconds left) {
    // Round up so a 300 us wait is not a busy 0 ms poll.
    return static_cast<int>((left.count() + 999) / 1000);
}

// A port that opened and worked, then failed (a pulled USB adapter, the
// emulator gone): the device is lost, which the run reports as a device
// failure (exit 4), not as a file it could not read or write (exit 5).
constexpr ErrorCode kLost = ErrorCode::hardware_fault;

// "process 123 (rollsense run ...)" holding a flock on the device file, from /proc/locks; empty if not found (its
// holder took no lock, as programs other than rollsense may not).
std::string lock_holder(const std::string& device) {
    struct stat st {};
    if (::stat(device.c_str(), &st) != 0) return {};
    char id[64];
    std::snprintf(id, sizeof id, " %02x:%02x:%llu ", major(st.st_dev), minor(st.st_dev),
                  static_cast<unsigned long long>(st.st_ino));
    std::ifstream locks("/proc/locks");
    for (std::string line; std::getline(locks, line);) {
        const auto at = line.find(id);
        if (line.find("FLOCK") == std::string::npos || at == std::string::npos) continue;
        const auto pid_at = line.rfind(' ', at - 1) + 1;  // "1: FLOCK  ADVISORY  WRITE <pid> <dev:inode> 0 EOF"
        const std::string pid = line.substr(pid_at, at - pid_at);
        if (pid == std::to_string(::getpid())) return "this process: two devices on one port?";
        std::ifstream cmdline("/proc/" + pid + "/cmdline");
        std::string command((std::istreambuf_iterator<char>(cmdline)), std::istreambuf_iterator<char>());
        std::replace(command.begin(), command.end(), '\0', ' ');
        while (!command.empty() && command.back() == ' ') command.pop_back();
        if (command.size() > 120) command = command.substr(0, 117) + "...";
        return "process " + pid + (command.empty() ? "" : " (" + command + ")");
    }
    return {};
}

std::string held_by(const std::string& holder) { return holder.empty() ? std::string() : " (" + holder + ")"; }

}  // namespace

Result<SerialPort> SerialPort::open(const std::string& device, std::uint32_t baud) {
    const int fd = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const int err = errno;
        std::string hint;
        if (err == ENOENT) hint = "; is the adapter plugged in? (ls /dev/ttyUSB* /dev/ttyACM*)";
        if (err == EACCES) hint = "; add yourself to the 'dialout' group (sudo usermod -aG dialout $USER) and log in again";
        if (err == EBUSY) hint = "; another program has the port open" + held_by(lock_holder(device));
        return Error{err == ENOENT ? ErrorCode::not_found : ErrorCode::io_error,
                     device + ": cannot open serial port: " + std::strerror(err) + hint};
    }
    // Exclusive for root too, whom TIOCEXCL (below) does not stop (hardware review: a second run as root drove the
    // servos beside the first, and both failed with bus errors that named no other program). Released at exit.
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        ::close(fd);
        if (err != EWOULDBLOCK) return Error{ErrorCode::io_error, device + ": cannot lock serial port: " + std::strerror(err)};
        return Error{ErrorCode::io_error, device + ": cannot open serial port: another program has it open" +
                                              held_by(lock_holder(device)) +
                                              "; stop it first: two programs on one bus corrupt each other's packets"};
    }
    return adopt(fd, device, baud);
}

Result<SerialPort> SerialPort::adopt(int fd, std::string name, std::uint32_t baud) {
    SerialPort port(fd, std::move(name), baud);
    const int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0)
        return Error{ErrorCode::io_error, port.name_ + ": fcntl failed: " + errno_text()};
    if (auto st = port.configure_raw(); !st.ok()) return st;
    if (auto st = port.set_baud(baud); !st.ok()) return st;
    // Exclusive: a second program writing to a half-duplex bus corrupts both.
    ioctl(fd, TIOCEXCL);
    tcflush(fd, TCIOFLUSH);
    return port;
}

SerialPort::~SerialPort() { close(); }

SerialPort::SerialPort(SerialPort&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), name_(std::move(other.name_)), baud_(other.baud_) {}

SerialPort& SerialPort::operator=(SerialPort&& other) noexcept {
    if (this != &other) {
        close();
        fd_ = std::exchange(other.fd_, -1);
        name_ = std::move(other.name_);
        baud_ = other.baud_;
    }
    return *this;
}

void SerialPort::close() noexcept {
    if (fd_ >= 0) {
        ioctl(fd_, TIOCNXCL);
        ::close(fd_);
    }
    fd_ = -1;
}

Status SerialPort::configure_raw() { return make_raw(fd_, name_); }

Status SerialPort::set_baud(std::uint32_t baud) {
    if (baud == 0) return {ErrorCode::invalid_argument, name_ + ": baud rate 0 is not a rate"};
    if (auto code = standard_speed_code(baud)) {
        termios tio{};
        if (tcgetattr(fd_, &tio) != 0) return {ErrorCode::io_error, name_ + ": tcgetattr: " + errno_text()};
        cfsetispeed(&tio, *code);
        cfsetospeed(&tio, *code);
        if (tcsetattr(fd_, TCSANOW, &tio) != 0)
            return {ErrorCode::io_error, name_ + ": cannot set " + std::to_string(baud) + " baud: " + errno_text()};
    } else if (auto st = set_custom_baud(fd_, baud); !st.ok()) {
        return std::move(st).with_context(name_);
    }
    baud_ = baud;
    return {};
}

Status SerialPort::write_all(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) {
    if (fd_ < 0) return {ErrorCode::state_error, "serial port is not open"};
    const auto deadline = Clock::now() + timeout;
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno != EAGAIN) return {kLost, name_ + ": write failed: " + errno_text()};
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - Clock::now());
        if (left.count() <= 0) return {ErrorCode::timeout, name_ + ": the port did not accept data in time"};
        pollfd p{fd_, POLLOUT, 0};
        ::poll(&p, 1, poll_ms(left));
    }
    return {};
}

Result<std::size_t> SerialPort::read_some(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout) {
    if (fd_ < 0) return Error{ErrorCode::state_error, "serial port is not open"};
    const auto deadline = Clock::now() + timeout;
    for (;;) {
        const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
        if (n > 0) return static_cast<std::size_t>(n);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK)
            return Error{kLost, name_ + ": read failed: " + errno_text() +
                                                  (errno == EIO ? " (device unplugged or emulator gone?)" : "")};
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - Clock::now());
        if (left.count() <= 0) return std::size_t{0};
        pollfd p{fd_, POLLIN, 0};
        const int r = ::poll(&p, 1, poll_ms(left));
        if (r < 0 && errno != EINTR) return Error{kLost, name_ + ": poll failed: " + errno_text()};
        if (r > 0 && (p.revents & (POLLERR | POLLNVAL)))
            return Error{kLost, name_ + ": the port reported an error (unplugged?)"};
        if (r > 0 && (p.revents & POLLHUP) && !(p.revents & POLLIN))
            return Error{kLost, name_ + ": the other end hung up"};
    }
}

Status SerialPort::read_exact(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    std::size_t done = 0;
    while (done < buffer.size()) {
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - Clock::now());
        if (left.count() <= 0)
            return {ErrorCode::timeout, name_ + ": got " + std::to_string(done) + " of " +
                                            std::to_string(buffer.size()) + " bytes before the timeout"};
        auto r = read_some(buffer.subspan(done), left);
        if (!r.ok()) return r.status();
        done += *r;
    }
    return {};
}

Status SerialPort::discard_input() {
    if (fd_ < 0) return {ErrorCode::state_error, "serial port is not open"};
    if (tcflush(fd_, TCIFLUSH) != 0) return {kLost, name_ + ": tcflush: " + errno_text()};
    return {};
}

Status SerialPort::drain() {
    if (fd_ < 0) return {ErrorCode::state_error, "serial port is not open"};
    if (tcdrain(fd_) != 0) return {kLost, name_ + ": tcdrain: " + errno_text()};
    return {};
}

}  // namespace rollsense::hal
