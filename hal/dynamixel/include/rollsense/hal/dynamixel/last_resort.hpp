// The last resort when the process crashes (SIGSEGV, SIGBUS, SIGABRT, SIGFPE):
// a torque-off packet prepared in advance for each open Dynamixel bus is
// written with write(2) from the signal handler (async-signal-safe: no heap,
// no locks, no Lua), then the signal takes its course (the previous handler,
// or the default action: a core dump). Best effort: a bus mid-packet may
// garble the first bytes, so the packet is sent twice. The Bus Watchdog
// covers what this cannot (SIGKILL, power loss). The same packets are the
// SDK's last resort (rollsense/last_resort.hpp), which the kernel runs on a Lua
// panic, std::terminate, an escaping std::bad_alloc, or when its cancel
// watchdog cannot get the bus from a stuck script thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace rollsense::hal::dxl {

// Register `packet` (at most kLastResortPacketMax bytes) to be written to `fd`
// on a crash; installs the handlers on first use. Returns a slot id (-1: no
// room or packet too long). Not async-signal-safe itself: call at activation.
inline constexpr std::size_t kLastResortPacketMax = 128;
int register_last_resort(int fd, std::span<const std::uint8_t> packet);
// Forget a slot (the bus is closing).
void unregister_last_resort(int slot);

}  // namespace rollsense::hal::dxl
