// device = "emulator": the profile's servos emulated in this process behind a
// pseudo-terminal, so the plugin's real serial and Protocol 2.0 code talks to
// them exactly as to rollsense-dxl-emu or a hand — but the servos move on the
// run clock, advanced at every read(). On the virtual clock the whole driver
// stack then runs as fast as the CPU allows and is deterministic (the stock
// experiment on emulated servos in minutes instead of hours).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "dynamixel_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"

namespace rollsense::dynamixel {

class InProcessEmulator {
public:
    // One emulated servo per joint (id, model, default mode, the bus's baud
    // rate, Return Delay Time 0), at its centre tick; with an object between
    // sensing_finger, pushing_finger and palm if the config asks for one.
    static Result<std::unique_ptr<InProcessEmulator>> start(const BusConfig& config);

    const std::string& device() const { return emulator_->device(); }
    // Move every servo on to run-clock time `time` (s), once the emulator has
    // handled the `bytes_sent` bytes the client has written so far.
    Status advance_to(double time, std::uint64_t bytes_sent);

private:
    explicit InProcessEmulator(std::unique_ptr<hal::dxl::PtyBusEmulator> e) : emulator_(std::move(e)) {}
    std::unique_ptr<hal::dxl::PtyBusEmulator> emulator_;
    std::optional<double> time_;
};

}  // namespace rollsense::dynamixel
