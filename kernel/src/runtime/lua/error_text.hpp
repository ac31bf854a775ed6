// Text for any Lua error value. A script may throw nil, a table, a userdata: strings and numbers read as they are; a
// value with __tostring reads through it, in protected mode (a __tostring that fails or is cancelled cannot escape
// into C++); anything else is named by its type.
#pragma once

#include <lua.hpp>

#include <string>

namespace rollsense::runtime {

std::string error_text(lua_State* L, int index);
// The same without calling __tostring (where hooks may be off: a cancel could not stop a __tostring that loops).
std::string error_text_raw(lua_State* L, int index);

}  // namespace rollsense::runtime
