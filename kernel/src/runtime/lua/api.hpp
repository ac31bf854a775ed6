// The `rollsense` Lua module (require "rollsense"): what roll scripts can do.
// docs/scripting.md is the user-facing reference; keep the two in step.
#pragma once

#include <lua.hpp>

#include "rollsense/status.hpp"

namespace rollsense::runtime {

class Session;

// Build the module for a session's sandbox.
void open_rollsense_api(Session& session);
// The session a Lua thread belongs to.
Session* session_of(lua_State* L);
// Raise a Status as a Lua error (file:line of the calling script is added).
[[noreturn]] void raise_status(lua_State* L, const Status& status);
// Close a finished or abandoned coroutine (runs its pending to-be-closed variables).
void close_thread(lua_State* thread, lua_State* from);

}  // namespace rollsense::runtime
