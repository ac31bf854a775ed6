// A raw serial port: 8 data bits, no parity, one stop bit, no flow control, no
// line discipline. Reads wait with poll() so every read has a timeout, which is
// what a half-duplex servo bus needs (a servo that does not answer must cost
// one timeout, never a hang).
//
// Works the same on a USB-serial adapter (/dev/ttyUSB0) and on the slave side
// of a pseudo-terminal (a pty accepts every termios call and ignores the rate).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "rollsense/hal/serial_link.hpp"
#include "rollsense/status.hpp"

namespace rollsense::hal {

class SerialPort final : public SerialLink {
public:
    SerialPort() = default;
    ~SerialPort() override;
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;
    SerialPort(SerialPort&& other) noexcept;
    SerialPort& operator=(SerialPort&& other) noexcept;

    // Open `device` in raw 8N1 at `baud` bits/s. Standard rates use the
    // classic termios speed codes; any other rate (e.g. 1000000 on a kernel
    // without B1000000, or 250000) goes through termios2/BOTHER.
    static Result<SerialPort> open(const std::string& device, std::uint32_t baud);

    // Take ownership of an already open tty descriptor (e.g. one end of a pty)
    // and put it in raw mode.
    static Result<SerialPort> adopt(int fd, std::string name, std::uint32_t baud);

    bool is_open() const noexcept { return fd_ >= 0; }
    const std::string& name() const noexcept override { return name_; }
    std::uint32_t baud() const noexcept override { return baud_; }
    int fd() const noexcept override { return fd_; }

    Status set_baud(std::uint32_t baud) override;

    // Write every byte (retrying short writes); waits at most `timeout` for the
    // device to accept them.
    Status write_all(std::span<const std::uint8_t> bytes,
                     std::chrono::milliseconds timeout = std::chrono::milliseconds(1000)) override;

    // Read whatever is available, waiting up to `timeout` for the first byte.
    // Returns the number of bytes read; 0 means the timeout expired.
    Result<std::size_t> read_some(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout) override;

    // Read exactly buffer.size() bytes, or fail with ErrorCode::timeout once
    // `timeout` has passed in total.
    Status read_exact(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout);

    // Drop bytes received but not yet read (stale replies after a timeout).
    Status discard_input() override;
    // Block until the kernel has sent everything written so far.
    Status drain();

    void close() noexcept;

private:
    SerialPort(int fd, std::string name, std::uint32_t baud) : fd_(fd), name_(std::move(name)), baud_(baud) {}
    Status configure_raw();

    int fd_ = -1;
    std::string name_;
    std::uint32_t baud_ = 0;
};

}  // namespace rollsense::hal
