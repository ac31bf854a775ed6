// The E-TRoll servo bus as rollsense-dxl-emu serves it by default, on a pty
// served by the test: the four servos at 1 Mbps without return delay, wire
// timing at the line rate, real time, an object clamped between the fingers.
// For tests that run the etroll-emulated profile end to end.
#pragma once

#include <catch2/catch.hpp>

#include <memory>

#include "rollsense/etroll_hand/clamped_object.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"

namespace etroll_bus {

inline std::unique_ptr<rollsense::hal::dxl::PtyBusEmulator> start() {
    using namespace rollsense::hal::dxl;
    BusEmulator bus;
    for (auto s : etroll_servos()) {
        s.baud_index = *index_from_baud(1'000'000);
        s.return_delay = 0;
        bus.add_servo(s);
    }
    REQUIRE(rollsense::etroll::clamp_object(bus, rollsense::etroll::ClampedObject{}).ok());
    PtyEmulatorOptions options;
    options.wire_baud_from_line = true;
    auto emu = PtyBusEmulator::start(std::move(bus), options);
    REQUIRE(emu.ok());
    return std::move(emu).value();
}

}  // namespace etroll_bus
