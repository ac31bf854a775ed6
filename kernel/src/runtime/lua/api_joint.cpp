// Joints from Lua: rs.joint(name) returns a handle with move / push / hold / torque and state queries. Every command
// goes through the kernel's limit checks (Robot::command_joint); a refused command raises and nothing moves.
#include <cmath>

#include "runtime/lua/api_internal.hpp"
#include "runtime/lua/lua_values.hpp"

namespace rollsense::runtime::lua_api {
namespace {

constexpr const char* kJointMeta = "rollsense.joint";

Joint& check_joint(lua_State* L, int index) { return **static_cast<Joint**>(luaL_checkudata(L, index, kJointMeta)); }

void push_joint(lua_State* L, Joint* j) {
    *static_cast<Joint**>(lua_newuserdatauv(L, sizeof(Joint*), 0)) = j;
    luaL_setmetatable(L, kJointMeta);
}

void command_or_raise(lua_State* L, Joint& j, const JointCommand& c) {
    auto st = Session::of(L).robot().command_joint(j, c);
    if (!st.ok()) raise_status(L, st);
}

// Have the task wait until every joint in `joints` has arrived (not moving,
// within tolerance of its goal); finish_wait raises on timeout.
bool wait_arrival(lua_State* L, std::vector<const Joint*> joints, double timeout_s, double tolerance,
                  const std::string& what) {
    Session& s = Session::of(L);
    LuaTask& t = waiting_task(L, "move");
    Wait w;
    w.kind = Wait::Kind::joints;
    w.joints = std::move(joints);
    w.tolerance = tolerance;
    w.until = s.now() + s.quantize(timeout_s);
    w.what = what + " (timeout " + format_number(timeout_s) + " s)";
    t.request(std::move(w));
    return true;
}

// A number option that must not be negative (`meaning_of_0` follows the refusal).
double opt_nonnegative(lua_State* L, int table, const char* key, double fallback, const char* meaning_of_0 = "") {
    const double v = opt_field_number(L, table, key, fallback);
    if (v < 0) luaL_error(L, "option '%s' is %f; it must be >= 0%s", key, v, meaning_of_0);
    return v;
}

// A wait's {timeout_ms=, tolerance=}: the timeout in s (HUGE_VAL: not given) and the tolerance, neither < 0.
std::pair<double, double> wait_options(lua_State* L, int table, double timeout_ms) {
    return {opt_nonnegative(L, table, "timeout_ms", timeout_ms) / 1000.0, opt_nonnegative(L, table, "tolerance", 0.5)};
}

// A timeout that fits the move: trapezoid duration plus a margin.
double default_timeout(const Joint& j, double goal, double velocity, double acceleration) {
    const double distance = std::abs(goal - j.state.position);
    if (velocity <= 0) return 10.0;
    double t = distance / velocity;
    if (acceleration > 0) t += velocity / acceleration;
    return 2.0 * t + 2.0;
}

// j:move(position, {velocity=, acceleration=, timeout_ms=, tolerance=, wait=true})
bool l_move(lua_State* L) {
    Joint& j = check_joint(L, 1);
    const double goal = luaL_checknumber(L, 2);
    check_options(L, 3, "move", {"velocity", "acceleration", "mode", "current", "wait", "timeout_ms", "tolerance"});
    const auto [timeout, tolerance] = wait_options(L, 3, HUGE_VAL);  // checked before anything moves
    const bool wait = opt_field_bool(L, 3, "wait", true);
    JointCommand c;
    c.mode = position_mode_of(j.info);
    c.position = goal;
    c.profile_velocity = opt_field_number(L, 3, "velocity", j.limit.max_velocity);
    c.profile_acceleration = opt_nonnegative(L, 3, "acceleration", 0, " (0: no limit)");
    const std::string mode = opt_field_string(L, 3, "mode", "");
    if (mode == "current_based_position") {
        c.mode = ControlMode::current_based_position;
        c.current = opt_field_number(L, 3, "current", j.limit.max_current);
    } else if (!mode.empty() && mode != "position" && mode != "extended_position") {
        luaL_error(L, "move: mode '%s' is not a position mode", mode.c_str());
    } else if (!mode.empty()) {
        c.mode = mode == "extended_position" ? ControlMode::extended_position : ControlMode::position;
    }
    if (c.mode != ControlMode::current_based_position && lua_istable(L, 3) && lua_getfield(L, 3, "current") != LUA_TNIL)
        luaL_error(L, "move: current= is the current limit of mode = 'current_based_position', not of this move's mode");
    lua_settop(L, 3);  // review: it was ignored silently
    command_or_raise(L, j, c);
    if (!wait) return false;
    char what[160];
    std::snprintf(what, sizeof what, "joint '%s' to reach %.3f %s", j.name.c_str(), goal, j.info.unit.c_str());
    return wait_arrival(L, {&j}, timeout < HUGE_VAL ? timeout : default_timeout(j, goal, j.command.profile_velocity,
                                                                                c.profile_acceleration), tolerance, what);
}

// j:push(current_mA): current (torque) mode, e.g. the pushing finger clamping;
// j:spin(velocity): velocity mode. The one number is the goal `field` of `mode`.
template <ControlMode mode, double JointCommand::*field>
int l_goal(lua_State* L) {
    Joint& j = check_joint(L, 1);
    JointCommand c;
    c.mode = mode;
    c.*field = luaL_checknumber(L, 2);
    c.position = j.state.position;
    command_or_raise(L, j, c);
    return 0;
}

// j:hold(): position mode at the present position.
int l_hold(lua_State* L) {
    Joint& j = check_joint(L, 1);
    command_or_raise(L, j, hold_command(j));
    return 0;
}

// j:torque(on)
int l_torque(lua_State* L) {
    Joint& j = check_joint(L, 1);
    JointCommand c = j.command;
    luaL_checktype(L, 2, LUA_TBOOLEAN);  // 0 and "off" are true in Lua: they must not switch torque on
    c.torque_enabled = lua_toboolean(L, 2) != 0;
    if (c.torque_enabled) c.position = std::clamp(j.state.position, j.limit.min, j.limit.max);
    command_or_raise(L, j, c);
    return 0;
}

// j:wait({timeout_ms=, tolerance=}): until the present goal is reached.
bool l_wait_arrived(lua_State* L) {
    Joint& j = check_joint(L, 1);
    check_options(L, 2, "wait", {"timeout_ms", "tolerance"});
    const auto [timeout, tolerance] = wait_options(L, 2, 10000);
    return wait_arrival(L, {&j}, timeout, tolerance, "joint '" + j.name + "' to arrive");
}

// j:position(), j:velocity(), j:current(): the last state read.
template <double JointState::*field>
int l_state_number(lua_State* L) {
    lua_pushnumber(L, check_joint(L, 1).state.*field);
    return 1;
}
int l_moving(lua_State* L) {
    lua_pushboolean(L, check_joint(L, 1).state.moving);
    return 1;
}
int l_name(lua_State* L) {
    lua_pushstring(L, check_joint(L, 1).name.c_str());
    return 1;
}

int l_state(lua_State* L) {
    const JointState& st = check_joint(L, 1).state;
    push_param_map(L, {{"position", st.position}, {"velocity", st.velocity}, {"current", st.current},
                       {"moving", st.moving}, {"torque", st.torque_enabled},
                       {"mode", std::string(to_string(st.mode))}, {"fault", st.fault}});
    return 1;
}

int l_limits(lua_State* L) {
    const Joint& j = check_joint(L, 1);
    push_param_map(L, {{"min", j.limit.min}, {"max", j.limit.max}, {"max_velocity", j.limit.max_velocity},
                       {"max_current", j.limit.max_current}, {"unit", j.info.unit}});
    return 1;
}

int l_tostring(lua_State* L) {
    const Joint& j = check_joint(L, 1);
    lua_pushfstring(L, "joint '%s' at %f %s", j.name.c_str(), j.state.position, j.info.unit.c_str());
    return 1;
}

// rs.joint(name)
int l_joint(lua_State* L) {
    const char* name = luaL_checkstring(L, 1);
    auto& robot = Session::of(L).robot();
    Joint* j = robot.find_joint(name);
    if (!j) return luaL_error(L, "no joint '%s' in this profile (joints: %s)", name, robot.joint_names().c_str());
    push_joint(L, j);
    return 1;
}

// rs.joints() → list of names
int l_joints(lua_State* L) {
    const auto& joints = Session::of(L).robot().joints();
    lua_createtable(L, static_cast<int>(joints.size()), 0);
    for (std::size_t i = 0; i < joints.size(); ++i) {
        lua_pushstring(L, joints[i].name.c_str());
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    return 1;
}

// rs.wait_joints({j1, j2, ...}, {timeout_ms=, tolerance=})
bool l_wait_joints(lua_State* L) {
    luaL_checktype(L, 1, LUA_TTABLE);
    std::vector<const Joint*> list;
    std::string names;
    for (lua_Integer i = 1; i <= static_cast<lua_Integer>(lua_rawlen(L, 1)); ++i) {
        if (lua_rawgeti(L, 1, i) != LUA_TUSERDATA || !luaL_testudata(L, -1, kJointMeta))  // review: "bad argument #-1"
            luaL_error(L, "rs.wait_joints: item %d is a %s, not a joint (rs.joint(name))", int(i), luaL_typename(L, -1));
        Joint& j = check_joint(L, -1);
        list.push_back(&j);
        names += (names.empty() ? "" : ", ") + j.name;
        lua_pop(L, 1);
    }
    check_options(L, 2, "rs.wait_joints", {"timeout_ms", "tolerance"});
    const auto [timeout, tolerance] = wait_options(L, 2, 10000);
    return wait_arrival(L, std::move(list), timeout, tolerance, "joints " + names + " to arrive");
}

}  // namespace

void register_joints(lua_State* L) {
    static const luaL_Reg methods[] = {{"move", waiting<l_move, finish_wait>},
                                       {"wait", waiting<l_wait_arrived, finish_wait>},
                                       {"push", l_goal<ControlMode::current, &JointCommand::current>},
                                       {"spin", l_goal<ControlMode::velocity, &JointCommand::velocity>},
                                       {"position", l_state_number<&JointState::position>},
                                       {"velocity", l_state_number<&JointState::velocity>},
                                       {"current", l_state_number<&JointState::current>},
                                       {"hold", l_hold},     {"torque", l_torque}, {"moving", l_moving},
                                       {"name", l_name},     {"state", l_state},   {"limits", l_limits},
                                       {nullptr, nullptr}};
    luaL_newmetatable(L, kJointMeta);
    protect_metatable(L);
    lua_newtable(L);
    luaL_setfuncs(L, methods, 0);
    refuse_unknown_names(L, -1, "joint:");
    lua_setfield(L, -2, "__index");
    lua_pushcfunction(L, l_tostring);
    lua_setfield(L, -2, "__tostring");
    lua_pop(L, 1);
    static const luaL_Reg fns[] = {{"joint", l_joint},
                                   {"joints", l_joints},
                                   {"wait_joints", waiting<l_wait_joints, finish_wait>},
                                   {nullptr, nullptr}};
    luaL_setfuncs(L, fns, 0);
}

}  // namespace rollsense::runtime::lua_api
