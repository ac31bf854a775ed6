// A BusEmulator behind a pseudo-terminal, served by its own thread: clients
// open slave_path() exactly as they would open /dev/ttyUSB0.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "rollsense/hal/dynamixel/bus_emulator.hpp"
#include "rollsense/hal/pty_pair.hpp"
#include "rollsense/status.hpp"

namespace rollsense::hal::dxl {

struct PtyEmulatorOptions {
    // true: servos move in wall-clock time. false: time stands still until the
    // owner calls with_bus([](BusEmulator& b) { b.advance(dt); }) (deterministic tests).
    bool real_time = true;
    // > 0: hold each reply back by the time the instruction and the reply would
    // take on a real wire at this rate plus the servo's Return Delay Time, so
    // the client sees realistic bus timing on a pty (which is otherwise instant).
    std::uint32_t wire_baud = 0;
    // true: time the wire at whatever rate the client set on the pty (its
    // termios speed), instead of a fixed wire_baud.
    bool wire_baud_from_line = false;
};

class PtyBusEmulator {
public:
    static Result<std::unique_ptr<PtyBusEmulator>> start(BusEmulator bus, PtyEmulatorOptions options = {});
    ~PtyBusEmulator();
    PtyBusEmulator(const PtyBusEmulator&) = delete;
    PtyBusEmulator& operator=(const PtyBusEmulator&) = delete;

    const std::string& device() const { return pty_.slave_path(); }
    void stop();
    // Bytes read from the client and fully handled (replies queued). A client
    // that drives the emulator's time itself waits for this to reach its own
    // bytes-sent count before advancing, so its last write is in effect.
    std::uint64_t bytes_handled() const { return bytes_handled_.load(); }

    // Run `f` on the bus with the serving thread held off.
    template <class F>
    auto with_bus(F&& f) {
        std::lock_guard lock(mutex_);
        return f(bus_);
    }

private:
    PtyBusEmulator(PtyPair pty, BusEmulator bus, PtyEmulatorOptions options)
        : pty_(std::move(pty)), bus_(std::move(bus)), options_(options) {}
    void serve();
    void send(const Bytes& bytes);

    PtyPair pty_;
    BusEmulator bus_;
    PtyEmulatorOptions options_;
    std::mutex mutex_;
    std::atomic<bool> running_{false};
    std::atomic<std::uint64_t> bytes_handled_{0};
    std::thread thread_;
    struct LateReply {
        std::chrono::steady_clock::time_point due;
        Bytes bytes;
    };
    std::deque<LateReply> late_;  // a `slow` servo's replies, in order (serving thread only)
};

}  // namespace rollsense::hal::dxl
