// What a half-duplex bus master needs from its line: write a packet, read
// what came back within a timeout, drop stale input, and a clock to measure
// that timeout on. A SerialPort is one (a tty, the wall clock); an emulator
// can be another that lives in memory and keeps its own time (the Dynamixel
// VirtualBusLink), so the master's protocol code runs unchanged on both.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <thread>

#include "rollsense/status.hpp"

namespace rollsense::hal {

class SerialLink {
public:
    using Clock = std::chrono::steady_clock;

    virtual ~SerialLink() = default;

    virtual const std::string& name() const noexcept = 0;
    virtual std::uint32_t baud() const noexcept = 0;
    virtual Status set_baud(std::uint32_t baud) = 0;

    // Write every byte; waits at most `timeout` for the line to accept them.
    virtual Status write_all(std::span<const std::uint8_t> bytes,
                             std::chrono::milliseconds timeout = std::chrono::milliseconds(1000)) = 0;
    // Read whatever is available, waiting up to `timeout` (on now()'s clock)
    // for the first byte. Returns the number of bytes read; 0 = timed out.
    virtual Result<std::size_t> read_some(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout) = 0;
    // Drop bytes received but not yet read (stale replies after a timeout).
    virtual Status discard_input() = 0;

    // The clock read_some() waits on, and a pause on it: the wall clock for a
    // real line; an emulated line may keep its own.
    virtual Clock::time_point now() const { return Clock::now(); }
    virtual void pause(std::chrono::nanoseconds d) { std::this_thread::sleep_for(d); }

    // A descriptor a crash handler may write(2) to, or -1 when the line has
    // none (an in-memory emulator dies with the process anyway).
    virtual int fd() const noexcept { return -1; }

    // Time one byte takes on the wire at the current rate (start + 8 data + stop bits).
    std::chrono::nanoseconds byte_time() const noexcept {
        return baud() == 0 ? std::chrono::nanoseconds(0) : std::chrono::nanoseconds(10'000'000'000LL / baud());
    }
};

}  // namespace rollsense::hal
