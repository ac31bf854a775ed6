// Devices and controllers from Lua: rs.device(name):call(verb, args) reaches a
// plugin's own operations; rs.controller(name, on) enables a C++ controller.
#include "runtime/lua/api_internal.hpp"
#include "runtime/lua/lua_values.hpp"

namespace rollsense::runtime::lua_api {
namespace {

constexpr const char* kDeviceMeta = "rollsense.device";

ComponentHandle& check_device(lua_State* L, int index) {
    return **static_cast<ComponentHandle**>(luaL_checkudata(L, index, kDeviceMeta));
}

int l_device(lua_State* L) {
    const char* name = luaL_checkstring(L, 1);
    auto& robot = Session::of(L).robot();
    ComponentHandle* h = robot.find_device(name);
    if (!h) {
        std::string known;
        for (const auto& n : robot.device_names()) known += (known.empty() ? "" : ", ") + n;
        return luaL_error(L, "no device '%s' in this profile (devices: %s)", name, known.c_str());
    }
    *static_cast<ComponentHandle**>(lua_newuserdatauv(L, sizeof(ComponentHandle*), 0)) = h;
    luaL_setmetatable(L, kDeviceMeta);
    return 1;
}

// device:call(verb, {args}) → table of results
int l_call(lua_State* L) {
    ComponentHandle& h = check_device(L, 1);
    const char* verb = luaL_checkstring(L, 2);
    auto args = lua_to_param_map(L, 3, std::string("call('") + verb + "') arguments");
    if (!args) raise_status(L, args.status());
    // The devices' lock only around the plugin call: a raised Lua error unwinds past this frame.
    auto result = [&] {
        const auto devices = Session::of(L).robot().lock_devices();
        return h.invoke(verb, *args);
    }();
    if (!result) raise_status(L, result.status());
    push_param_map(L, *result);
    return 1;
}

int l_state(lua_State* L) {
    ComponentHandle& h = check_device(L, 1);
    lua_pushstring(L, std::string(to_string(h.state())).c_str());
    return 1;
}

int l_recover(lua_State* L) {
    ComponentHandle& h = check_device(L, 1);
    auto s = [&] {
        const auto devices = Session::of(L).robot().lock_devices();
        return h.recover();
    }();
    if (!s.ok()) raise_status(L, s);
    return 0;
}

// rs.controller(name, enable)
int l_controller(lua_State* L) {
    Session& s = Session::of(L);
    const char* name = luaL_checkstring(L, 1);
    const bool on = lua_isnone(L, 2) || (luaL_checktype(L, 2, LUA_TBOOLEAN), lua_toboolean(L, 2) != 0);  // not 0, "off"
    const bool known = s.robot().find_controller(name);  // unknown, switched off too (diff review): enable refuses it
    if (!on && known) s.robot().disable_controller(name, s.now());
    else if (auto st = s.robot().enable_controller(name, s.now()); !st.ok())  // unknown: the script's, as rs.joint's
        raise_status(L, known ? st : Status(ErrorCode::script_error, st.message()));
    return 0;
}

// rs.controller_telemetry(name) → table of numbers
int l_controller_telemetry(lua_State* L) {
    Session& s = Session::of(L);
    const char* name = luaL_checkstring(L, 1);
    Controller* c = s.robot().find_controller(name);
    if (!c) return luaL_error(L, "no controller '%s' in this profile", name);
    lua_newtable(L);
    for (const auto& [k, v] : c->telemetry()) {
        lua_pushnumber(L, v);
        lua_setfield(L, -2, k.c_str());
    }
    return 1;
}

}  // namespace

void register_devices(lua_State* L) {
    static const luaL_Reg methods[] = {{"call", l_call}, {"state", l_state}, {"recover", l_recover}, {nullptr, nullptr}};
    luaL_newmetatable(L, kDeviceMeta);
    protect_metatable(L);
    lua_newtable(L);
    luaL_setfuncs(L, methods, 0);
    refuse_unknown_names(L, -1, "device:");
    lua_setfield(L, -2, "__index");
    lua_pop(L, 1);
    static const luaL_Reg fns[] = {{"device", l_device},
                                   {"controller", l_controller},
                                   {"controller_telemetry", l_controller_telemetry},
                                   {nullptr, nullptr}};
    luaL_setfuncs(L, fns, 0);
}

}  // namespace rollsense::runtime::lua_api
