// A bus of emulated servos: takes instruction packets, answers with status
// packets exactly as X-series firmware would, and injects faults on request.
// Transport-free (bytes in, bytes out) so it runs in-process in unit tests and
// behind a pseudo-terminal in the `rollsense-dxl-emu` program.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "rollsense/hal/dynamixel/emulated_servo.hpp"
#include "rollsense/hal/dynamixel/injected_fault.hpp"
#include "rollsense/hal/dynamixel/protocol.hpp"

namespace rollsense::hal::dxl {

// Faults injected on one servo. Counts are consumed reply by reply; -1 = forever.
struct FaultPlan {
    int drop_replies = 0;     // answer nothing (the client times out)
    int corrupt_replies = 0;  // answer with a wrong CRC (the client sees a CRC error)
    std::chrono::microseconds late{0};  // hold every reply back this long (a transport honours it)
};

class BusEmulator {
public:
    BusEmulator() = default;

    void add_servo(const ServoSetup& setup);
    // nullptr if no servo has that id.
    EmulatedServo* servo(std::uint8_t id);
    const EmulatedServo* servo(std::uint8_t id) const;
    std::vector<std::uint8_t> ids() const;

    // Feed received bytes; returns the bytes to send back, one entry per
    // status packet in the order the servos answer.
    std::vector<Bytes> receive(std::span<const std::uint8_t> bytes);
    // Handle one parsed instruction packet.
    std::vector<Bytes> handle(const Packet& instruction);

    // The rate the client's line runs at (0 = unknown: every servo listens).
    // A servo set to another Baud Rate sees only noise and never answers,
    // as on a real bus.
    void set_line_baud(std::uint32_t baud) { line_baud_ = baud; }

    // A mechanical coupling between servos on this bus (for instance an object
    // held between two fingers, which the HAL knows nothing about): called
    // before every step of the servos' motion models, at most kCouplingStep of
    // emulated time apart, to move obstacles with the servos that push them.
    // An empty function: none.
    using Coupling = std::function<void(BusEmulator&)>;
    static constexpr double kCouplingStep = 0.001;  // s
    void set_coupling(Coupling coupling) { coupling_ = std::move(coupling); }

    // Advance every servo's motion model (and the coupling between them).
    void advance(double seconds);

    // ---- fault injection
    void set_faults(std::uint8_t id, FaultPlan plan) { faults_[id] = plan; }
    void raise_hardware_error(std::uint8_t id, std::uint8_t bits);
    // A fault that starts once `after_s` of emulated time (advance()) has passed.
    void schedule(const InjectedFault& fault) { scheduled_.push_back({fault, false}); }
    // How long a reply from servo `id` is held back (a `slow` servo).
    std::chrono::microseconds late_by(std::uint8_t id) const;
    // Emulated time since the start (the sum of advance() steps).
    double elapsed() const { return elapsed_; }
    // Bytes sent in front of the next status packet (line noise).
    void inject_garbage(Bytes bytes) { garbage_ = std::move(bytes); }

    // Counters, for tests and the emulator's status line.
    std::uint64_t instructions_handled() const { return handled_; }
    std::uint64_t crc_errors_seen() const { return crc_errors_; }
    std::uint64_t sync_writes() const { return sync_writes_; }
    std::uint64_t sync_reads() const { return sync_reads_; }

private:
    // Build a status packet for `s`, applying its fault plan; false = no reply.
    // The servo with this id if it can hear the line at its rate.
    EmulatedServo* listener(std::uint8_t id);
    bool hears(const EmulatedServo& s) const;
    bool reply(EmulatedServo& s, std::uint8_t error, std::span<const std::uint8_t> params, std::vector<Bytes>& out);

    void apply_due_faults();

    struct Scheduled {
        InjectedFault fault;
        bool applied = false;
    };
    std::vector<EmulatedServo> servos_;
    std::vector<Scheduled> scheduled_;
    double elapsed_ = 0;
    Coupling coupling_;
    std::map<std::uint8_t, FaultPlan> faults_;
    Bytes garbage_;
    std::uint32_t line_baud_ = 0;
    PacketParser parser_;
    std::uint64_t handled_ = 0, crc_errors_ = 0, sync_writes_ = 0, sync_reads_ = 0;
};

}  // namespace rollsense::hal::dxl
