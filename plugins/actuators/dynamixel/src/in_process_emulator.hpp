// device = "emulator": the profile's servos emulated in this process on an
// in-memory line (hal::dxl::VirtualBusLink), so the plugin's real Protocol 2.0
// code talks to them exactly as to rollsense-dxl-emu or a hand — but a write
// is answered at once, reply timeouts run on the link's own clock, and the
// servos move on the run clock (advance_servos_to at every read()). On the
// virtual clock the whole driver stack then runs as fast as the CPU allows and
// is deterministic (the stock experiment on emulated servos in well under a
// minute instead of hours).
#pragma once

#include <memory>

#include "dynamixel_config.hpp"
#include "rollsense/hal/dynamixel/virtual_link.hpp"

namespace rollsense::dynamixel {

// One emulated servo per joint (id, model, default mode, the bus's baud rate,
// Return Delay Time 0), at its centre tick; with an object between
// sensing_finger, pushing_finger and palm if the config asks for one, and the
// config's injected faults scheduled. Errors start with the parameter's key.
Result<std::unique_ptr<hal::dxl::VirtualBusLink>> start_in_process_emulator(const BusConfig& config);

}  // namespace rollsense::dynamixel
