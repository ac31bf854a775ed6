#include "runtime/lua/lua_values.hpp"

#include <algorithm>
#include <charconv>
#include <vector>

namespace rollsense::runtime {

Result<ParamValue> lua_to_param(lua_State* L, int index, const std::string& where) {
    index = lua_absindex(L, index);
    switch (lua_type(L, index)) {
        case LUA_TBOOLEAN: return ParamValue{static_cast<bool>(lua_toboolean(L, index))};
        case LUA_TNUMBER:
            if (lua_isinteger(L, index)) return ParamValue{static_cast<std::int64_t>(lua_tointeger(L, index))};
            return ParamValue{static_cast<double>(lua_tonumber(L, index))};
        case LUA_TSTRING: return ParamValue{std::string(lua_tostring(L, index))};
        case LUA_TTABLE: {
            const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, index));
            // Only sequences: a table with other keys is a nested structure.
            lua_Integer count = 0;
            for (lua_pushnil(L); lua_next(L, index); lua_pop(L, 1)) ++count;
            if (count != n)
                return Error{ErrorCode::invalid_argument,
                             where + ": a nested table is not a parameter value (use a flat list like {1, 2, 3})"};
            std::vector<std::int64_t> ints;
            std::vector<double> nums;
            std::vector<std::string> strs;
            bool all_int = true, all_num = true, all_str = true;
            for (lua_Integer i = 1; i <= n; ++i) {
                lua_rawgeti(L, index, i);
                const int t = lua_type(L, -1);
                all_str = all_str && t == LUA_TSTRING;
                all_num = all_num && t == LUA_TNUMBER;
                all_int = all_int && t == LUA_TNUMBER && lua_isinteger(L, -1);
                if (t == LUA_TSTRING) strs.emplace_back(lua_tostring(L, -1));
                if (t == LUA_TNUMBER) nums.push_back(lua_tonumber(L, -1)), ints.push_back(lua_tointeger(L, -1));
                lua_pop(L, 1);
            }
            if (n == 0) return ParamValue{std::vector<double>{}};
            if (all_int) return ParamValue{ints};
            if (all_num) return ParamValue{nums};
            if (all_str) return ParamValue{strs};
            return Error{ErrorCode::invalid_argument,
                         where + ": a list must hold only numbers or only strings"};
        }
        default:
            return Error{ErrorCode::invalid_argument,
                         where + ": a " + std::string(luaL_typename(L, index)) + " is not a parameter value"};
    }
}

Result<std::map<std::string, ParamValue>> lua_to_param_map(lua_State* L, int index, const std::string& where) {
    index = lua_absindex(L, index);
    std::map<std::string, ParamValue> out;
    if (lua_isnoneornil(L, index)) return out;
    if (!lua_istable(L, index))
        return Error{ErrorCode::invalid_argument, where + ": expected a table, got a " +
                                                      std::string(luaL_typename(L, index))};
    lua_pushnil(L);
    while (lua_next(L, index)) {
        if (lua_type(L, -2) != LUA_TSTRING) {
            lua_pop(L, 2);
            return Error{ErrorCode::invalid_argument, where + ": keys must be names (strings)"};
        }
        std::string key = lua_tostring(L, -2);
        auto v = lua_to_param(L, -1, where + "." + key);
        lua_pop(L, 1);
        if (!v) {
            lua_pop(L, 1);
            return v.error();
        }
        out.emplace(std::move(key), std::move(*v));
    }
    return out;
}

namespace {
struct Pusher {
    lua_State* L;
    void operator()(bool b) const { lua_pushboolean(L, b); }
    void operator()(std::int64_t i) const { lua_pushinteger(L, static_cast<lua_Integer>(i)); }
    void operator()(double d) const { lua_pushnumber(L, d); }
    void operator()(const std::string& s) const { lua_pushlstring(L, s.data(), s.size()); }
    template <class T>
    void operator()(const std::vector<T>& l) const {
        lua_createtable(L, static_cast<int>(l.size()), 0);
        for (std::size_t i = 0; i < l.size(); ++i) {
            (*this)(l[i]);
            lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
        }
    }
};
}  // namespace

void push_param(lua_State* L, const ParamValue& value) { std::visit(Pusher{L}, value); }

void push_param_map(lua_State* L, const std::map<std::string, ParamValue>& values) {
    lua_createtable(L, 0, static_cast<int>(values.size()));
    for (const auto& [k, v] : values) {
        push_param(L, v);
        lua_setfield(L, -2, k.c_str());
    }
}

namespace {
ParamValue parse_scalar(const std::string& t) {
    if (t.size() >= 2 && t.front() == '"' && t.back() == '"') return t.substr(1, t.size() - 2);  // text as written
    if (t == "true") return true;
    if (t == "false") return false;
    std::int64_t i = 0;
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), i);
    if (ec == std::errc() && p == t.data() + t.size() && !t.empty()) return i;
    double d = 0;
    auto [p2, ec2] = std::from_chars(t.data(), t.data() + t.size(), d);
    if (ec2 == std::errc() && p2 == t.data() + t.size() && !t.empty()) return d;
    return t;
}
std::string trim(std::string s) {
    while (!s.empty() && s.front() == ' ') s.erase(s.begin());
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}
}  // namespace

ParamValue parse_cli_value(const std::string& text) {
    if (text.size() >= 2 && text.front() == '{' && text.back() == '}') {
        std::vector<ParamValue> items;
        const std::string inner = text.substr(1, text.size() - 2);
        for (std::size_t start = 0, comma = 0; start <= inner.size(); start = comma + 1) {
            comma = std::min(inner.find(',', start), inner.size());
            if (auto item = trim(inner.substr(start, comma - start)); !item.empty()) items.push_back(parse_scalar(item));
        }
        // The list of the narrowest type all items have: integers, numbers, else strings.
        std::vector<std::int64_t> ints;
        std::vector<double> nums;
        std::vector<std::string> strs;
        for (const auto& v : items) {
            if (const auto* i = std::get_if<std::int64_t>(&v)) ints.push_back(*i), nums.push_back(static_cast<double>(*i));
            if (const auto* d = std::get_if<double>(&v)) nums.push_back(*d);
            strs.push_back(std::holds_alternative<std::string>(v) ? std::get<std::string>(v) : format_param_value(v));
        }
        if (items.empty()) return std::vector<double>{};
        if (ints.size() == items.size()) return ints;
        if (nums.size() == items.size()) return nums;
        return strs;
    }
    return parse_scalar(text);
}

}  // namespace rollsense::runtime
