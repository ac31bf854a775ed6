// The last resort: actions a device prepares at activation that make it safe with no heap, no locks and no Lua (e.g. a
// torque-off packet written with write(2)). The kernel runs them when its ordinary safe state cannot be trusted: a Lua
// panic, std::terminate, an escaping std::bad_alloc, a script thread stuck inside a plugin call. They must be
// async-signal-safe and may run twice.
#pragma once

#include "rollsense/export.hpp"

namespace rollsense {

using LastResortAction = void (*)(void* context) noexcept;
// A slot id, or -1 when all 16 are taken. Not async-signal-safe: call while setting up.
ROLLSENSE_API int add_last_resort(LastResortAction action, void* context);
ROLLSENSE_API void remove_last_resort(int slot);
// Every registered action, in slot order; returns how many ran.
ROLLSENSE_API int run_last_resort() noexcept;

}  // namespace rollsense
