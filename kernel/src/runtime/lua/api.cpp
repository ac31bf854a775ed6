// Module assembly and the core of the rollsense Lua API: time, waiting, settings, logging, progress, tasks and cleanup.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

#include "rollsense/log.hpp"
#include "rollsense/random.hpp"
#include "runtime/lua/api_internal.hpp"
#include "runtime/lua/lua_values.hpp"

namespace rollsense::runtime {

namespace {
const char kSessionKey = 0;  // its address is the registry key
}

Session* session_of(lua_State* L) {
    lua_rawgetp(L, LUA_REGISTRYINDEX, &kSessionKey);
    auto* s = static_cast<Session*>(lua_touserdata(L, -1));
    lua_pop(L, 1);
    return s;
}

void raise_status(lua_State* L, const Status& status) {
    if (auto* s = session_of(L)) s->set_raised(status);
    luaL_error(L, "%s", status.message().c_str());
    throw StatusError(status);  // not reached: luaL_error does not return
}

void close_thread(lua_State* thread, lua_State* /*from*/) {
    lua_resetthread(thread);  // Lua 5.4.4; 5.4.6 renames it lua_closethread(thread, from)
}

void open_rollsense_api(Session& session) {
    lua_State* L = session.sandbox().state();
    lua_pushlightuserdata(L, &session);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &kSessionKey);
    lua_newtable(L);
    for (auto add : {&lua_api::register_core, &lua_api::register_joints, &lua_api::register_trials,
                     &lua_api::register_devices, &lua_api::register_extras})
        add(L);
    lua_api::refuse_unknown_names(L, -1, "rs.");
    session.sandbox().set_api_module(luaL_ref(L, LUA_REGISTRYINDEX));
}

namespace lua_api {

namespace {
std::vector<Registrar>& extras() {
    static std::vector<Registrar> list;
    return list;
}
}  // namespace

ExtraRegistration::ExtraRegistration(Registrar registrar) { extras().push_back(registrar); }
void register_extras(lua_State* L) { for (auto r : extras()) r(L); }

namespace {
// Edits (insert, delete, replace) between two names.
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = std::exchange(row[0], i);
        for (std::size_t j = 1; j <= b.size(); ++j)
            diagonal = std::exchange(row[j], std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])}));
    }
    return row[b.size()];
}

// __index(table, key): the nearest name of the table, if one is near. Names are strings: other keys read nil
// (ipairs(rs) ends at once, as before).
int unknown_name(lua_State* L) {
    luaL_checktype(L, 1, LUA_TTABLE);
    if (lua_type(L, 2) != LUA_TSTRING) return lua_pushnil(L), 1;
    const char* prefix = lua_tostring(L, lua_upvalueindex(1));
    const std::string name = lua_tostring(L, 2);
    std::string nearest;
    std::size_t best = std::max<std::size_t>(2, name.size() / 3) + 1;  // farther: no suggestion
    for (lua_pushnil(L); lua_next(L, 1); lua_pop(L, 1)) {
        if (lua_type(L, -2) != LUA_TSTRING) continue;
        const std::string candidate = lua_tostring(L, -2);
        const std::size_t d = edit_distance(name, candidate);
        if (d < best || (d == best && !nearest.empty() && candidate < nearest)) best = d, nearest = candidate;
    }
    const std::string hint = nearest.empty() ? "" : " (did you mean " + std::string(prefix) + nearest + "?)";
    return luaL_error(L, "%s%s does not exist%s; docs/scripting.md lists the API", prefix, name.c_str(), hint.c_str());
}
}  // namespace

void refuse_unknown_names(lua_State* L, int table, const char* prefix) {
    table = lua_absindex(L, table);
    lua_newtable(L);
    protect_metatable(L);  // review: getmetatable(rs).__index(42, "x") crashed liblua
    lua_pushstring(L, prefix);
    lua_pushcclosure(L, unknown_name, 1);
    lua_setfield(L, -2, "__index");
    lua_setmetatable(L, table);
}

LuaTask& waiting_task(lua_State* L, const char* function) {
    Session& s = Session::of(L);
    auto* t = dynamic_cast<LuaTask*>(s.scheduler().current());
    if (!t || t->thread() != L || !lua_isyieldable(L))
        luaL_error(L, "%s cannot wait here (not inside a procedure: e.g. in a wait_until condition or a "
                      "function called from C such as a table.sort comparator)", function);
    return *t;
}

namespace {
LuaTask* resumed_task(lua_State* L) { return dynamic_cast<LuaTask*>(Session::of(L).scheduler().current()); }

// Why a wait ended cancelled: the cancel's reason, or the failure that ends the run (a wait_until condition's error).
int raise_cancelled(lua_State* L, Session& s) {
    const Sandbox& box = s.sandbox();
    return luaL_error(L, "cancelled: %s", (box.cancelled() ? box.cancel_reason() : s.scheduler().failure().message()).c_str());
}
}  // namespace

int finish_wait(lua_State* L, int, lua_KContext) {
    Session& s = Session::of(L);
    LuaTask* t = resumed_task(L);
    if (!t) return 0;
    if (t->outcome() == WaitOutcome::cancelled) return raise_cancelled(L, s);
    if (t->outcome() == WaitOutcome::timed_out)
        raise_status(L, Status(ErrorCode::timeout, "timed out waiting for " + t->waiting_for()));
    return 0;
}

void check_options(lua_State* L, int table, const char* call, std::initializer_list<const char*> valid) {
    if (!lua_istable(L, table)) return;
    table = lua_absindex(L, table);
    for (lua_pushnil(L); lua_next(L, table); lua_pop(L, 1)) {
        const char* key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : nullptr;
        bool ok = false;
        for (const char* v : valid) ok = ok || (key && std::strcmp(key, v) == 0);
        if (ok) continue;
        std::string names;
        for (const char* v : valid) names += (names.empty() ? "" : ", ") + std::string(v);
        luaL_error(L, "%s: unknown option '%s' (options: %s)", call, key ? key : luaL_tolstring(L, -2, nullptr),
                   names.c_str());
    }
}

namespace {
// Pushes option `key` of the option table at `table` (nil without a table); true when it is not nil.
bool push_option(lua_State* L, int table, const char* key) {
    if (lua_isnoneornil(L, table)) return lua_pushnil(L), false;
    luaL_checktype(L, table, LUA_TTABLE);
    return lua_getfield(L, table, key) != LUA_TNIL;
}
}  // namespace

const char* shown_value(lua_State* L, int index) {
    const int type = lua_type(L, index);
    return type == LUA_TNUMBER || type == LUA_TBOOLEAN ? luaL_tolstring(L, index, nullptr)
           : type == LUA_TSTRING ? lua_pushfstring(L, "'%s'", lua_tostring(L, index))
                                 : lua_pushfstring(L, "a %s", luaL_typename(L, index));
}

double opt_field_number(lua_State* L, int table, const char* key, double fallback) {
    const bool given = push_option(L, table, key);
    const double v = given ? lua_tonumber(L, -1) : fallback;
    if (given && (!lua_isnumber(L, -1) || !std::isfinite(v)))  // NaN or infinity would pass every range check
        luaL_error(L, "option '%s' must be a finite number, not %s", key, shown_value(L, -1));
    lua_pop(L, 1);
    return v;
}

bool opt_field_bool(lua_State* L, int table, const char* key, bool fallback) {
    const bool given = push_option(L, table, key);
    if (given && !lua_isboolean(L, -1))  // 0 and "off" are true in Lua: a switch takes true or false only
        luaL_error(L, "option '%s' must be true or false, not %s", key, shown_value(L, -1));
    const bool v = given ? lua_toboolean(L, -1) != 0 : fallback;
    lua_pop(L, 1);
    return v;
}

std::string opt_field_string(lua_State* L, int table, const char* key, const std::string& fallback) {
    const bool given = push_option(L, table, key);
    if (given && !lua_isstring(L, -1)) luaL_error(L, "option '%s' must be a string", key);
    std::size_t length = 0;
    const char* text = given ? lua_tolstring(L, -1, &length) : nullptr;
    if (text && std::strlen(text) != length) luaL_error(L, "option '%s' holds a NUL byte", key);  // a file name cut short
    std::string v = text ? std::string(text, length) : fallback;
    lua_pop(L, 1);
    return v;
}

namespace {

// rs.now() → run clock in seconds
int l_now(lua_State* L) {
    lua_pushnumber(L, Session::of(L).now());
    return 1;
}

// rs.wait(ms)
bool l_wait(lua_State* L) {
    const double ms = luaL_checknumber(L, 1);
    if (!(ms >= 0) || !std::isfinite(ms)) luaL_error(L, "rs.wait: milliseconds must be a number >= 0");
    Session& s = Session::of(L);
    // 0 (or less than the clock's step): the next control period, so a polling loop lets the joints move on the
    // virtual clock too (review: it hung).
    const double d = s.quantize(ms / 1000.0), until = d > 0 ? s.now() + d : s.scheduler().next_control();
    waiting_task(L, "rs.wait").request(Wait::for_time(until));
    return true;
}

int after_wait_until(lua_State* L, int, lua_KContext) {
    Session& s = Session::of(L);
    LuaTask* t = resumed_task(L);
    t->release_predicate();
    if (t->outcome() == WaitOutcome::cancelled) return raise_cancelled(L, s);
    lua_pushboolean(L, t->outcome() == WaitOutcome::ready);
    return 1;
}

// rs.wait_until(condition, timeout_ms) → true, or false on timeout. The condition is checked once per control period;
// it must not wait itself.
bool l_wait_until(lua_State* L) {
    luaL_checktype(L, 1, LUA_TFUNCTION);
    const bool timed = !lua_isnoneornil(L, 2);
    const double ms = timed ? luaL_checknumber(L, 2) : 0;
    if (timed && (!(ms >= 0) || !std::isfinite(ms)))  // review: NaN and -5 meant "forever"
        luaL_error(L, "rs.wait_until: timeout_ms must be a number >= 0, or nil for no timeout");
    Session& s = Session::of(L);
    LuaTask& t = waiting_task(L, "rs.wait_until");
    lua_pushvalue(L, 1);
    const int ref = luaL_ref(L, LUA_REGISTRYINDEX);
    t.hold_predicate(ref);
    Wait w;
    w.kind = Wait::Kind::predicate;
    // The script's line that called it, through pcall and other C functions.
    w.predicate = lua_predicate(s.sandbox(), ref, script_line(L, 1).data());
    w.until = timed ? s.now() + s.quantize(ms / 1000.0) : HUGE_VAL;
    w.what = "a condition";
    t.request(std::move(w));
    return true;
}

// rs.setting(key, default): a --set value (of the default's type where that is a number or boolean: another is the
// command line's error), or the declared default (rs.settings), or `default`. No default: required. In a namespace that
// declared its settings, an undeclared key is an error.
int l_setting(lua_State* L) {
    const Settings& st = Session::of(L).settings();
    const std::string key = luaL_checkstring(L, 1);
    const auto declared = st.declared().find(key);
    if (declared == st.declared().end() && st.namespace_declared(key)) {
        std::string names;
        for (const auto& [k, v] : st.declared())
            if (setting_namespace(k) == setting_namespace(key)) names += (names.empty() ? "" : ", ") + k;
        return luaL_error(L, "rs.setting: '%s' is not declared (declared: %s); add it to rs.settings{...}",
                          key.c_str(), names.c_str());
    }
    if (const ParamValue* v = st.find(key)) {
        push_param(L, *v);
        if (const int want = lua_type(L, 2); declared == st.declared().end() && lua_type(L, -1) != want &&
                                             (want == LUA_TNUMBER || want == LUA_TBOOLEAN))
            raise_status(L, {ErrorCode::bad_setting, "--set " + key + ": a " + luaL_typename(L, -1) + " where rs.setting('" +
                                                         key + "', ...) reads a " + lua_typename(L, want) + " (its default's type)"});
        return 1;
    }
    if (declared != st.declared().end()) {
        push_param(L, declared->second);
        return 1;
    }
    if (lua_gettop(L) < 2) raise_status(L, {ErrorCode::bad_setting, "setting '" + key + "' is required: pass --set " + key + "=VALUE"});
    lua_settop(L, 2);
    return 1;
}

int l_seed(lua_State* L) {
    lua_pushinteger(L, static_cast<lua_Integer>(Session::of(L).options().seed));
    return 1;
}

int l_profile(lua_State* L) {
    Session& s = Session::of(L);
    lua_newtable(L);
    lua_pushstring(L, s.profile().name.c_str());
    lua_setfield(L, -2, "name");
    lua_pushstring(L, s.profile().description.c_str());
    lua_setfield(L, -2, "description");
    lua_pushboolean(L, s.profile().virtual_clock);
    lua_setfield(L, -2, "virtual_clock");
    lua_pushnumber(L, s.profile().sample_rate_hz);
    lua_setfield(L, -2, "sample_rate_hz");
    lua_pushnumber(L, s.profile().control_rate_hz);
    lua_setfield(L, -2, "control_rate_hz");
    lua_newtable(L);
    int i = 0;
    for (const auto& c : s.profile().controllers) {
        lua_pushstring(L, c.name.c_str());
        lua_rawseti(L, -2, ++i);
    }
    lua_setfield(L, -2, "controllers");
    return 1;
}

int l_log(lua_State* L) {
    log_info("script", script_log_entry(L, ' '));
    return 0;
}
int l_warn(lua_State* L) {
    log_warning("script", script_log_entry(L, ' '));
    return 0;
}

// rs.progress(done, total, label)
int l_progress(lua_State* L) {
    const auto done = luaL_checkinteger(L, 1);
    const auto total = luaL_checkinteger(L, 2);
    const char* label = luaL_optstring(L, 3, "");
    if (done < 0 || total < 0 || done > total) return luaL_error(L, "rs.progress: need 0 <= done <= total");
    Session::of(L).report_progress(static_cast<std::size_t>(done), static_cast<std::size_t>(total), label);
    return 0;
}

// rs.spawn(fn): run fn as a concurrent task (it ends when the main procedure ends).
int l_spawn(lua_State* L) {
    luaL_checktype(L, 1, LUA_TFUNCTION);
    const char* name = luaL_optstring(L, 2, "task");
    if (auto st = Session::of(L).spawn(L, 1, name); !st.ok()) raise_status(L, st);
    return 0;
}

// rs.on_cleanup(fn): fn runs when the script ends, however it ends (error, Ctrl-C, e-stop included), after the kernel
// has stopped every joint.
int l_on_cleanup(lua_State* L) {
    luaL_checktype(L, 1, LUA_TFUNCTION);
    lua_pushvalue(L, 1);
    Session::of(L).add_cleanup(luaL_ref(L, LUA_REGISTRYINDEX));
    return 0;
}

// rs.write_output(name, text): a text file in the run's output folder.
int l_write_output(lua_State* L) {
    std::size_t name_length = 0;
    const char* given = luaL_checklstring(L, 1, &name_length);
    const std::string name(given, name_length);  // whole: a NUL in it is refused as no plain name (sandbox review)
    size_t len = 0;
    const char* text = luaL_checklstring(L, 2, &len);
    Session& s = Session::of(L);
    // Checked before the text is copied out of the Lua heap.
    if (auto st = Session::check_output_name(name, "rs.write_output"); !st.ok()) raise_status(L, st);
    if (auto st = s.sandbox().charge(len, "rs.write_output('" + name + "')"); !st.ok()) raise_status(L, st);
    auto st = s.write_output_text(name, std::string(text, len));
    if (!st.ok()) raise_status(L, st);
    return 0;
}

int l_output_dir(lua_State* L) {
    const auto& dir = Session::of(L).output_dir();
    if (dir.empty())
        lua_pushnil(L);
    else
        lua_pushstring(L, dir.c_str());
    return 1;
}

// rs.random() → uniform [0, 1); rs.random_normal() → N(0, 1) by Box–Muller, two draws each (std::normal_distribution's
// algorithm is the standard library's choice: another would draw other numbers). Seeded per trial.
int l_random(lua_State* L) { return lua_pushnumber(L, random::unit_interval(Session::of(L).trial_random()())), 1; }
int l_random_normal(lua_State* L) {
    auto& rng = Session::of(L).trial_random();
    const double u1 = 1.0 - random::unit_interval(rng()), u2 = random::unit_interval(rng());  // u1 in (0, 1]: finite log
    lua_pushnumber(L, std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2));
    return 1;
}

}  // namespace

void register_core(lua_State* L) {
    static const luaL_Reg fns[] = {
        {"now", l_now}, {"wait", waiting<l_wait, finish_wait>}, {"wait_until", waiting<l_wait_until, after_wait_until>},
        {"setting", l_setting}, {"seed", l_seed}, {"profile", l_profile}, {"log", l_log}, {"warn", l_warn},
        {"progress", l_progress}, {"spawn", l_spawn}, {"on_cleanup", l_on_cleanup}, {"write_output", l_write_output},
        {"output_dir", l_output_dir}, {"random", l_random}, {"random_normal", l_random_normal}, {nullptr, nullptr}};
    luaL_setfuncs(L, fns, 0);
}

}  // namespace lua_api
}  // namespace rollsense::runtime
