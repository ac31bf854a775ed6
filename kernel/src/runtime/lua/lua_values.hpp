// Conversions between Lua values and the SDK's typed ParamValue.
#pragma once

#include <lua.hpp>

#include <map>
#include <string>

#include "rollsense/params.hpp"

namespace rollsense::runtime {

// Convert the value at `index` to a ParamValue. Sequences of numbers or strings become lists; nested tables and
// functions are refused with a message naming `where` (e.g. "sim.lua: devices.tactile.params.gain").
Result<ParamValue> lua_to_param(lua_State* L, int index, const std::string& where);
// A table of key → value (string keys only) at `index`.
Result<std::map<std::string, ParamValue>> lua_to_param_map(lua_State* L, int index, const std::string& where);

void push_param(lua_State* L, const ParamValue& value);
void push_param_map(lua_State* L, const std::map<std::string, ParamValue>& values);

// Parse a command-line value: integer, number, true/false, {a, b, c} list, or string.
ParamValue parse_cli_value(const std::string& text);

}  // namespace rollsense::runtime
