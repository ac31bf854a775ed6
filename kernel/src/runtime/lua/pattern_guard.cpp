#include "runtime/lua/pattern_guard.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace rollsense::runtime {

double pattern_cost_log10(std::string_view p, std::size_t n, bool every_start) {
    int repeats = 0, optional = 0;
    bool anchored = false;
    std::size_t i = 0;
    if (!p.empty() && p[0] == '^') {
        anchored = true;
        i = 1;
    }
    while (i < p.size()) {
        const char c = p[i];
        // One single-character item: %x, [set], or a plain character.
        if (c == '%' && i + 1 < p.size()) {
            if (p[i + 1] == 'b') {  // %bxy scans to the balancing character
                ++repeats;
                i += 4;
                continue;
            }
            if (p[i + 1] == 'f') {  // %f[set]: a frontier, matches no character
                i += 2;
                if (i < p.size() && p[i] == '[') {
                    ++i;
                    if (i < p.size() && p[i] == '^') ++i;
                    if (i < p.size() && p[i] == ']') ++i;
                    while (i < p.size() && p[i] != ']') i += p[i] == '%' ? 2 : 1;
                    ++i;
                }
                continue;
            }
            if (p[i + 1] >= '1' && p[i + 1] <= '9') ++repeats;  // a back-reference compares up to n bytes (review)
            i += 2;
        } else if (c == '[') {
            ++i;
            if (i < p.size() && p[i] == '^') ++i;
            if (i < p.size() && p[i] == ']') ++i;  // a leading ']' is part of the set
            while (i < p.size() && p[i] != ']') i += p[i] == '%' ? 2 : 1;
            ++i;
        } else if (c == '(' || c == ')') {
            ++i;
            continue;  // captures match no character
        } else {
            ++i;
        }
        if (i < p.size()) {
            if (p[i] == '*' || p[i] == '+' || p[i] == '-') {
                ++repeats;
                ++i;
            } else if (p[i] == '?') {
                ++optional;
                ++i;
            }
        }
    }
    const int exponent = repeats + ((every_start || !anchored) ? 1 : 0);
    const double cost = exponent * std::log10(static_cast<double>(n) + 1.0) + optional * std::log10(2.0);
    return cost > kPatternBudgetLog10 ? cost : 0.0;
}

namespace {

// Upvalue 1: the real function; upvalue 2: its name; upvalue 3: true for
// gmatch (every start position, whatever the anchor).
int guarded(lua_State* L) {
    std::size_t n = 0, plen = 0;
    luaL_checklstring(L, 1, &n);
    const char* pattern = luaL_checklstring(L, 2, &plen);
    const char* name = lua_tostring(L, lua_upvalueindex(2));
    const bool gmatch = lua_toboolean(L, lua_upvalueindex(3));
    const bool plain = std::string_view(name) == "string.find" && lua_toboolean(L, 4);
    if (!plain) {
        if (const double cost = pattern_cost_log10({pattern, plen}, n, gmatch); cost > 0) {
            char msg[512];
            std::snprintf(msg, sizeof msg,
                          "%s: pattern '%s' is too costly on a subject of %zu bytes (backtracking bound 10^%.1f "
                          "steps, the sandbox allows 10^%.0f): use fewer repetitions (*, +, -, ?, %%b), anchor it "
                          "with '^', match a shorter subject, or use a plain find",
                          name, std::string(pattern, plen).substr(0, 60).c_str(), n, cost, kPatternBudgetLog10);
            return luaL_error(L, "%s", msg);
        }
    }
    const int nargs = lua_gettop(L);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, nargs, LUA_MULTRET);
    return lua_gettop(L);
}

}  // namespace

void guard_string_patterns(lua_State* L) {
    const int lib = lua_gettop(L);
    for (const char* fn : {"find", "match", "gmatch", "gsub"}) {
        lua_getfield(L, lib, fn);
        lua_pushstring(L, (std::string("string.") + fn).c_str());
        lua_pushboolean(L, std::string_view(fn) == "gmatch");
        lua_pushcclosure(L, &guarded, 3);
        lua_setfield(L, lib, fn);
    }
}

}  // namespace rollsense::runtime
