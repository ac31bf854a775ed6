#include "runtime/lua/error_text.hpp"

namespace rollsense::runtime {
namespace {

int tostring_protected(lua_State* L) {
    luaL_tolstring(L, 1, nullptr);
    return 1;
}

}  // namespace

std::string error_text_raw(lua_State* L, int index) {
    const int type = lua_type(L, index);
    if (type == LUA_TSTRING || type == LUA_TNUMBER) {
        lua_pushvalue(L, index);  // lua_tolstring converts a number in place: work on a copy
        std::size_t n = 0;
        const char* s = lua_tolstring(L, -1, &n);
        std::string text(s, n);
        lua_pop(L, 1);
        return text;
    }
    return std::string("(error object is a ") + lua_typename(L, type) + " value)";
}

std::string error_text(lua_State* L, int index) {
    index = lua_absindex(L, index);
    const int type = lua_type(L, index);
    if (type == LUA_TSTRING || type == LUA_TNUMBER || !lua_checkstack(L, 3)) return error_text_raw(L, index);
    if (luaL_getmetafield(L, index, "__tostring") == LUA_TNIL) return error_text_raw(L, index);
    lua_pop(L, 1);
    lua_pushcfunction(L, &tostring_protected);
    lua_pushvalue(L, index);
    const bool ok = lua_pcall(L, 1, 1, 0) == LUA_OK && lua_type(L, -1) == LUA_TSTRING;
    const std::string text = error_text_raw(L, -1);  // the text, or why __tostring failed
    lua_pop(L, 1);
    if (ok) return text;
    return std::string("(error object is a ") + lua_typename(L, type) + " value whose __tostring failed: " + text + ")";
}

}  // namespace rollsense::runtime
