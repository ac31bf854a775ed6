// Trials and recording from Lua: rs.trial{...}, rs.trial_id{...}, rs.record_start/stop,
// rs.save_trial, rs.end_trial, rs.has_trial (for --resume and --shard), rs.shard(), rs.recorded().
#include <algorithm>
#include <cmath>

#include "rollsense/trial_id.hpp"
#include "runtime/lua/api_internal.hpp"

namespace rollsense::runtime::lua_api {
namespace {

void check(lua_State* L, const Status& s) { if (!s.ok()) raise_status(L, s); }

// object, speed (a label, or a number as Lua spells it: 10 → "10") and repetition at index 1, as a manifest holds them.
void read_trial_key(lua_State* L, TrialInfo& info, const char* call) {
    luaL_checktype(L, 1, LUA_TTABLE);
    info.object = opt_field_string(L, 1, "object", "");
    lua_getfield(L, 1, "speed");
    const int type = lua_type(L, -1);
    if (type == LUA_TNUMBER ? !std::isfinite(lua_tonumber(L, -1)) : type != LUA_TSTRING && type != LUA_TNIL)
        luaL_error(L, "%s: speed is %s: give a number or a label (a string)", call, shown_value(L, -1));
    if (type != LUA_TNIL) info.speed = luaL_tolstring(L, -1, nullptr), lua_pop(L, 1);
    lua_pop(L, 1);
    lua_getfield(L, 1, "repetition");
    const double rep = lua_isnil(L, -1) ? 0 : lua_isnumber(L, -1) ? lua_tonumber(L, -1) : -1;
    if (!(rep >= 0 && rep <= INT32_MAX && rep == std::floor(rep)))
        luaL_error(L, "%s: repetition is %s: give a whole number in [0, 2147483647]", call, shown_value(L, -1));
    info.repetition = static_cast<int>(rep);
    lua_pop(L, 1);
}

// rs.trial_id{object=, speed=, repetition=} → the id rs.trial{} gives such a trial
int l_trial_id(lua_State* L) {
    TrialInfo info;
    check_options(L, 1, "rs.trial_id", {"object", "speed", "repetition"});
    read_trial_key(L, info, "rs.trial_id");
    if (info.object.empty()) return luaL_error(L, "rs.trial_id: give an object (and speed, repetition)");
    lua_pushstring(L, trial_id(info.object, info.speed, info.repetition).c_str());
    return 1;
}

// rs.trial{object=, speed=, repetition=, id=, extra={k=v}} → id
int l_trial(lua_State* L) {
    TrialInfo info;
    check_options(L, 1, "rs.trial", {"object", "speed", "repetition", "id", "extra"});
    read_trial_key(L, info, "rs.trial");
    info.id = opt_field_string(L, 1, "id", "");
    if (info.id.empty()) {
        if (info.object.empty()) return luaL_error(L, "rs.trial: give an id, or an object (and speed, repetition)");
        info.id = trial_id(info.object, info.speed, info.repetition);
    }
    // Extras are copied into the trial and its manifest row, outside the Lua
    // heap: bounded, so a script cannot grow C++ memory past its cap.
    constexpr std::size_t kMaxExtra = 4096, kMaxExtras = 64 * 1024;
    std::size_t extras_bytes = 0;
    // Names to text, numbers or booleans (review: a table was written as 'table: 0x...', other keys dropped).
    if (lua_getfield(L, 1, "extra") != LUA_TNIL && !lua_istable(L, -1))
        return luaL_error(L, "rs.trial: extra is a %s, not a table {name = value}", luaL_typename(L, -1));
    if (lua_istable(L, -1)) {
        lua_pushnil(L);
        while (lua_next(L, -2)) {
            const int vt = lua_type(L, -1);
            if (lua_type(L, -2) != LUA_TSTRING || (vt != LUA_TSTRING && vt != LUA_TNUMBER && vt != LUA_TBOOLEAN))
                return luaL_error(L, "rs.trial: extra holds a %s key with a %s value: give name = text, number or "
                                     "boolean", luaL_typename(L, -2), luaL_typename(L, -1));
            std::size_t klen = 0, vlen = 0;
            const char* key = lua_tolstring(L, -2, &klen);
            const char* value = luaL_tolstring(L, -1, &vlen);
            extras_bytes += klen + vlen;
            if (vlen > kMaxExtra || extras_bytes > kMaxExtras)
                return luaL_error(L, "rs.trial: extra '%s' is %d bytes (%d in all); extras go into the manifest row, at "
                                     "most %d bytes each and %d bytes in all: write large data with rs.write_output",
                                  std::string(key, std::min<std::size_t>(klen, 60)).c_str(), int(vlen), int(extras_bytes),
                                  int(kMaxExtra), int(kMaxExtras));
            info.extra[std::string(key, klen)] = std::string(value, vlen);
            lua_pop(L, 2);  // the value and its text
        }
    }
    lua_pop(L, 1);
    std::string id = info.id;
    check(L, Session::of(L).begin_trial(std::move(info)));
    lua_pushstring(L, id.c_str());
    return 1;
}

int l_has_trial(lua_State* L) {
    lua_pushboolean(L, Session::of(L).has_trial(luaL_checkstring(L, 1)));
    return 1;
}

// rs.shard() → k, n: this process records the trials whose index ≡ k (mod n); 0, 1 unsharded.
int l_shard(lua_State* L) {
    const auto shard = Session::of(L).options().shard.value_or(Shard{});
    lua_pushinteger(L, static_cast<lua_Integer>(shard.index));
    lua_pushinteger(L, static_cast<lua_Integer>(shard.count));
    return 2;
}

// rs.record_start(), rs.save_trial(), rs.end_trial(): a step of the session's trial.
template <Status (Session::*step)()>
int l_trial_step(lua_State* L) {
    check(L, (Session::of(L).*step)());
    return 0;
}

int l_record_stop(lua_State* L) {
    Session& s = Session::of(L);
    check(L, s.record_stop());
    lua_pushinteger(L, static_cast<lua_Integer>(s.recorded().samples()));
    return 1;
}

void push_column(lua_State* L, const std::vector<double>& v) {
    lua_createtable(L, static_cast<int>(v.size()), 0);
    for (std::size_t i = 0; i < v.size(); ++i) {
        lua_pushnumber(L, v[i]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
}

// rs.recorded() → { time = {...}, ch1 = {...}, ..., <joint> = {...}, samples = n }
int l_recorded(lua_State* L) {
    Session& s = Session::of(L);
    const auto& d = s.recorded();
    const auto& robot = s.robot();
    lua_newtable(L);
    push_column(L, d.time);
    lua_setfield(L, -2, "time");
    for (std::size_t c = 0; c < d.channels.size() && c < robot.channel_columns().size(); ++c) {
        push_column(L, d.channels[c]);
        lua_setfield(L, -2, robot.channel_columns()[c].c_str());
    }
    for (std::size_t j = 0; j < d.joints.size() && j < robot.recorded_joints().size(); ++j) {
        push_column(L, d.joints[j]);
        lua_setfield(L, -2, robot.recorded_joints()[j].c_str());
    }
    lua_pushinteger(L, static_cast<lua_Integer>(d.samples()));
    lua_setfield(L, -2, "samples");
    return 1;
}

}  // namespace

void register_trials(lua_State* L) {
    static const luaL_Reg fns[] = {
        {"trial", l_trial}, {"trial_id", l_trial_id}, {"has_trial", l_has_trial}, {"shard", l_shard},
        {"record_start", l_trial_step<&Session::record_start>}, {"record_stop", l_record_stop},
        {"save_trial", l_trial_step<&Session::save_trial>}, {"end_trial", l_trial_step<&Session::end_trial>},
        {"recorded", l_recorded}, {nullptr, nullptr}};
    luaL_setfuncs(L, fns, 0);
}

}  // namespace rollsense::runtime::lua_api
