// Shared helpers of the Lua bindings (api_*.cpp). Not part of any public API.
#pragma once

#include <lua.hpp>

#include <initializer_list>
#include <string>

#include "runtime/lua/api.hpp"
#include "runtime/session/session.hpp"

namespace rollsense::runtime::lua_api {

// The task running this Lua code; raises if the caller cannot wait here
// (inside a wait_until condition, at load time of a module, ...).
LuaTask& waiting_task(lua_State* L, const char* function);
// A binding that may wait: `request` checks its arguments and, to wait, gives the task its Wait and returns true; the
// task then yields, `k` continuing. The Lua library yields by throwing a C++ exception: yielding here, where no C++
// object is alive, spares the unwinder a second walk for every destructor.
template <bool (*request)(lua_State*), lua_KFunction k>
int waiting(lua_State* L) { return request(L) ? lua_yieldk(L, 0, 0, k) : 0; }
// Continuation that turns a cancelled or timed-out wait into an error and returns nothing otherwise.
int finish_wait(lua_State* L, int status, lua_KContext ctx);

// On the metatable at the top of the stack: getmetatable() returns a string and setmetatable() is refused, so a
// script cannot reach __gc or rewrite methods of an object the kernel owns. Every userdata metatable sets this.
inline void protect_metatable(lua_State* L) {
    lua_pushliteral(L, "rollsense object (protected metatable)");
    lua_setfield(L, -2, "__metatable");
}

// Reading a name the table at `table` lacks raises "rs.record_strat does not exist (did you mean rs.record_start?)"
// instead of giving nil (Lua's later "attempt to call a nil value" suggests nothing). `prefix`: "rs.", "joint:".
void refuse_unknown_names(lua_State* L, int table, const char* prefix);

// Raises "CALL: unknown option 'velocty' (options: velocity, ...)" for a key of
// the option table at `table` that is not in `valid` (nothing when it is no table).
void check_options(lua_State* L, int table, const char* call, std::initializer_list<const char*> valid);
// A refused value as a message shows it, pushed: a number or boolean itself, a string quoted, anything else its
// type ("a table": a table's address says nothing).
const char* shown_value(lua_State* L, int index);
double opt_field_number(lua_State* L, int table, const char* key, double fallback);
bool opt_field_bool(lua_State* L, int table, const char* key, bool fallback);
std::string opt_field_string(lua_State* L, int table, const char* key, const std::string& fallback);

// Registration of each part of the module on the table at the top of the stack.
void register_core(lua_State* L);
void register_joints(lua_State* L);
void register_trials(lua_State* L);
void register_devices(lua_State* L);
// Extra parts (e.g. identification) register through this hook list.
using Registrar = void (*)(lua_State* L);
struct ExtraRegistration {
    explicit ExtraRegistration(Registrar registrar);
};
void register_extras(lua_State* L);

}  // namespace rollsense::runtime::lua_api
