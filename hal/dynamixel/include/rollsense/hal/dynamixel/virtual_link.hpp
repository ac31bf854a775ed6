// A BusEmulator on the far end of an in-memory line, on a clock of its own:
// the fast twin of PtyBusEmulator for runs on the virtual clock.
//
// A write hands its bytes straight to the emulator's packet parser; the
// replies to every packet completed by them are queued at once, all of them
// (the four status packets of a SYNC_READ come back in one read_some()). No
// thread, no pseudo-terminal, no polling: the client's Protocol 2.0 code
// (framing, byte stuffing, CRC, retries) runs unchanged, and a servo that does
// not answer costs one reply timeout on the link's clock, which moves only
// while the client waits (read_some, pause) — so timeouts are deterministic
// and cost no wall time. Replies of a `slow` servo are due late_by() after the
// instruction on that clock, as the pty emulator holds them back on the wall clock.
//
// The servos themselves move on a second time line, set by the owner
// (advance_servos_to): the run clock, as with PtyBusEmulator(real_time = false).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "rollsense/hal/dynamixel/bus_emulator.hpp"
#include "rollsense/hal/serial_link.hpp"

namespace rollsense::hal::dxl {

class VirtualBusLink final : public SerialLink {
public:
    VirtualBusLink(BusEmulator bus, std::uint32_t baud, std::string name = "emulator");

    const std::string& name() const noexcept override { return name_; }
    std::uint32_t baud() const noexcept override { return baud_; }
    Status set_baud(std::uint32_t baud) override;
    Status write_all(std::span<const std::uint8_t> bytes,
                     std::chrono::milliseconds timeout = std::chrono::milliseconds(1000)) override;
    Result<std::size_t> read_some(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout) override;
    Status discard_input() override;
    Clock::time_point now() const override { return now_; }
    void pause(std::chrono::nanoseconds d) override { now_ += std::chrono::duration_cast<Clock::duration>(d); }

    // Move every servo on to `seconds` of servo time (the first call only sets
    // the origin; time never runs backwards).
    void advance_servos_to(double seconds);
    BusEmulator& bus() noexcept { return bus_; }
    const BusEmulator& bus() const noexcept { return bus_; }
    // Reply bytes queued and not yet read, due or not.
    std::size_t pending_bytes() const;

private:
    struct Reply {
        Clock::time_point due;
        Bytes bytes;
        std::size_t read = 0;  // bytes of it already handed out
    };
    std::size_t take_due(std::span<std::uint8_t> buffer);

    BusEmulator bus_;
    std::uint32_t baud_;
    std::string name_;
    Clock::time_point now_{};
    std::optional<double> servo_time_;
    std::deque<Reply> replies_;  // in order of due time
};

}  // namespace rollsense::hal::dxl
