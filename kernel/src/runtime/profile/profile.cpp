#include "runtime/profile/profile.hpp"

#include <lua.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <chrono>
#include <memory>
#include <type_traits>

#include "runtime/lua/lua_values.hpp"
#include "runtime/lua/sandbox.hpp"

namespace rollsense::runtime {
namespace fs = std::filesystem;

Status Settings::add(const std::string& kv) {
    auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
        return {ErrorCode::invalid_argument, "--set expects key=value, got '" + kv + "'"};
    values_[kv.substr(0, eq)] = parse_cli_value(kv.substr(eq + 1));
    return {};
}

const ParamValue* Settings::find(const std::string& key) const {
    auto it = values_.find(key);
    if (it == values_.end()) return nullptr;
    used_.insert(key);
    return &it->second;
}

std::vector<std::string> Settings::unused() const {
    std::vector<std::string> out;
    for (const auto& [k, v] : values_)
        if (!used_.count(k)) out.push_back(k);
    return out;
}

bool Settings::namespace_declared(const std::string& key) const {
    const auto ns = setting_namespace(key);
    for (const auto& [k, v] : declared_)
        if (setting_namespace(k) == ns) return true;
    return false;
}

std::string setting_namespace(const std::string& key) {
    const auto dot = key.find('.');
    return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

bool is_profile_path(const std::string& key) {
    static const std::set<std::string> entries = {"description", "clock",   "sample_rate_hz", "control_rate_hz",
                                                  "plugin_path", "devices", "joints",         "record_joints",
                                                  "controllers", "safety",  "identification_channels"};
    return entries.count(key.substr(0, key.find('.'))) > 0;  // an entry (sample_rate_hz) or a path under one
}

fs::path resolve_profile_path(const std::string& name, const fs::path& share_dir) {
    if (name.find('/') != std::string::npos || (name.size() > 4 && name.substr(name.size() - 4) == ".lua"))
        return fs::path(name);
    return share_dir / "profiles" / (name + ".lua");
}

namespace {

// "profile 'x' not found at P (profiles here: a, b)", for --profile and include().
std::string profile_not_found(const std::string& name, const fs::path& path, const fs::path& share_dir) {
    std::string known;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(share_dir / "profiles", ec))
        if (e.path().extension() == ".lua") known += (known.empty() ? "" : ", ") + e.path().stem().string();
    return "profile '" + name + "' not found at " + path.string() + (path.is_relative() ? " (relative to the working folder "
           + fs::current_path(ec).string() + ")" : "") + (known.empty() ? "" : " (profiles here: " + known + ")");
}

struct LuaCloser {
    void operator()(lua_State* L) const { lua_close(L); }
};

// The same two limits a script runs under: a heap cap (an allocation past it fails: "not enough memory") and a
// wall-time budget checked from an instruction hook, for the whole evaluation of the profile and its includes.
struct ProfileBudget {
    LuaHeap heap;
    double max_ms = 0;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
};

ProfileBudget* budget_of(lua_State* L) { return *static_cast<ProfileBudget**>(lua_getextraspace(L)); }

void budget_hook(lua_State* L, lua_Debug*) {
    auto* b = budget_of(L);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - b->start).count();
    if (ms > b->max_ms) {
        luaL_where(L, 0);  // in a hook, level 0 is the running function: the profile's (or an include's) file:line
        lua_pushfstring(L, "the profile ran %d ms without finishing (an endless loop?), past --slice-limit-ms %d",
                        static_cast<int>(ms), static_cast<int>(b->max_ms));
        lua_concat(L, 2), lua_error(L);
    }
}

struct LoadState {
    fs::path share_dir;
    const Settings* settings;
    int depth = 0;
    std::map<const void*, TableSource> sources;  // each table a profile file returned: that file's text
};

int run_profile_file(lua_State* L, const fs::path& path);

// include("name"): evaluate another profile and return its table.
int lua_include(lua_State* L) {
    auto* st = static_cast<LoadState*>(lua_touserdata(L, lua_upvalueindex(1)));
    const char* name = luaL_checkstring(L, 1);
    if (++st->depth > 8) return luaL_error(L, "include('%s'): profiles include each other too deeply", name);
    auto path = resolve_profile_path(name, st->share_dir);
    if (std::error_code ec; !fs::exists(path, ec))  // luaL_error names the including file and line
        return luaL_error(L, "include: %s", profile_not_found(name, path, st->share_dir).c_str());
    int n = run_profile_file(L, path);
    --st->depth;
    return n;
}

// setting("key", default): a --set value or the default.
int lua_setting(lua_State* L) {
    auto* st = static_cast<LoadState*>(lua_touserdata(L, lua_upvalueindex(1)));
    const char* key = luaL_checkstring(L, 1);
    if (const ParamValue* v = st->settings->find(key)) {
        push_param(L, *v);
        return 1;
    }
    if (lua_gettop(L) < 2) return luaL_error(L, "setting '%s' is required: pass --set %s=VALUE", key, key);
    lua_settop(L, 2);
    return 1;
}

int run_profile_file(lua_State* L, const fs::path& path) {
    if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) return lua_error(L);
    // A fresh environment: only the helpers, no standard library.
    lua_newtable(L);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_pushcclosure(L, lua_include, 1);
    lua_setfield(L, -2, "include");
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_pushcclosure(L, lua_setting, 1);
    lua_setfield(L, -2, "setting");
    lua_setupvalue(L, -2, 1);
    lua_call(L, 0, 1);
    if (!lua_istable(L, -1)) return luaL_error(L, "%s: a profile must return a table", path.c_str());
    auto* st = static_cast<LoadState*>(lua_touserdata(L, lua_upvalueindex(1)));
    if (st->sources.try_emplace(lua_topointer(L, -1), TableSource::scan(path)).second)  // the first file returning it made it
        lua_pushvalue(L, -1), luaL_ref(L, LUA_REGISTRYINDEX);  // kept alive: its address names it to the end
    return 1;
}

// Walks a Lua table and remembers which keys were read, so that leftovers can be reported as unknown.
class TableReader {
public:
    TableReader(lua_State* L, int index, const Profile& p, std::string path)
        : L_(L), index_(lua_absindex(L, index)), p_(p), path_(std::move(path)) {}

    std::string path(const std::string& key) const { return path_.empty() || key.empty() ? path_ + key : path_ + "." + key; }
    std::string at(const std::string& key) const { return p_.at(path(key)); }

    // Pushes the field (or nil); remember to pop.
    int push(const std::string& key) {
        used_.insert(key);
        return lua_getfield(L_, index_, key.c_str());
    }
    Result<std::optional<double>> number(const std::string& key) { return field<double>(key, LUA_TNUMBER, "a number"); }
    Result<std::optional<std::string>> string(const std::string& key) { return field<std::string>(key, LUA_TSTRING, "a string"); }
    Result<std::optional<bool>> boolean(const std::string& key) { return field<bool>(key, LUA_TBOOLEAN, "true or false"); }
    // A field of Lua type `type` (empty when absent), else an error saying what it must be.
    template <class T>
    Result<std::optional<T>> field(const std::string& key, int type, const char* must_be) {
        const int t = push(key);
        std::optional<T> out;
        if (t == type) {
            if constexpr (std::is_same_v<T, double>) out = lua_tonumber(L_, -1);
            else if constexpr (std::is_same_v<T, bool>) out = lua_toboolean(L_, -1) != 0;
            else out = lua_tostring(L_, -1);
        }
        lua_pop(L_, 1);
        if (t != type && t != LUA_TNIL) return Error{ErrorCode::invalid_argument, at(key) + " must be " + must_be};
        return out;
    }
    Result<std::vector<std::string>> string_list(const std::string& key) {
        push(key);
        auto v = lua_isnil(L_, -1) ? Result<ParamValue>(ParamValue{std::vector<std::string>{}})
                                   : lua_to_param(L_, -1, at(key));
        lua_pop(L_, 1);
        if (!v) return v.error();
        if (auto* l = std::get_if<std::vector<std::string>>(&*v)) return *l;
        if (auto* l = std::get_if<std::vector<double>>(&*v); l && l->empty()) return std::vector<std::string>{};
        return Error{ErrorCode::invalid_argument, at(key) + " must be a list of strings"};
    }
    // Iterate over string keys of a sub-table: fn(name, reader-of-value-at-top).
    template <class F>
    Status each(const std::string& key, F&& fn) {
        if (const int t = push(key); t != LUA_TTABLE) {
            lua_pop(L_, 1);
            return t == LUA_TNIL ? Status{} : Status{ErrorCode::invalid_argument, at(key) + " must be a table"};
        }
        int table = lua_gettop(L_);
        // Sorted keys: deterministic device order regardless of Lua's hashing.
        std::vector<std::string> names;
        for (lua_pushnil(L_); lua_next(L_, table);) {
            lua_pop(L_, 1);
            if (lua_type(L_, -1) != LUA_TSTRING) {
                lua_pop(L_, 2);
                return {ErrorCode::invalid_argument, at(key) + ": entries must be named (name = { ... })"};
            }
            names.emplace_back(lua_tostring(L_, -1));
        }
        std::sort(names.begin(), names.end());
        Status s;
        for (auto name = names.begin(); s.ok() && name != names.end(); ++name) {
            lua_getfield(L_, table, name->c_str());
            s = fn(*name, path(key) + "." + *name);
            lua_settop(L_, table);
        }
        lua_pop(L_, 1);
        return s;
    }
    Status reject_unknown() {
        for (lua_pushnil(L_); lua_next(L_, index_);) {
            lua_pop(L_, 1);
            std::string key = lua_type(L_, -1) == LUA_TSTRING ? lua_tostring(L_, -1) : "<non-name key>";
            if (!used_.count(key)) {
                lua_pop(L_, 1);
                std::string known;
                for (const auto& k : used_) known += (known.empty() ? "" : ", ") + k;
                return {ErrorCode::invalid_argument, at(key) + ": unknown key (known here: " + known + ")"};
            }
        }
        return {};
    }

private:
    lua_State* L_;
    int index_;
    const Profile& p_;
    std::string path_;  // from the profile's table: "devices.tactile"
    std::set<std::string> used_;
};

// Return early on error. The status variable's name carries the line number
// because TRY nests (a TRY inside a lambda passed to TRY).
#define TRY_CAT2(a, b) a##b
#define TRY_CAT(a, b) TRY_CAT2(a, b)
#define TRY(expr)                                                                   \
    do {                                                                            \
        if (auto TRY_CAT(status_, __LINE__) = (expr); !TRY_CAT(status_, __LINE__).ok()) \
            return TRY_CAT(status_, __LINE__);                                      \
    } while (0)

template <class T>
Status take(Result<T> r, T& out) {
    if (!r) return r.status();
    out = std::move(*r);
    return {};
}

Status read_gpio(lua_State* L, TableReader r, bool is_trigger, std::optional<GpioLine>& out) {
    if (!lua_istable(L, -1)) return {ErrorCode::invalid_argument, r.at("") + " must be a table { chip = ..., line = ... }"};
    std::optional<std::string> chip;
    std::optional<double> line, pulse;
    std::optional<bool> active_low;
    TRY(take(r.string("chip"), chip));
    TRY(take(r.number("line"), line));
    TRY(take(r.boolean("active_low"), active_low));
    if (is_trigger) TRY(take(r.number("pulse_ms"), pulse));
    TRY(r.reject_unknown());
    if (!chip || !line) return {ErrorCode::invalid_argument, r.at("") + " needs chip and line"};
    out = GpioLine{*chip, static_cast<unsigned>(*line), active_low.value_or(false), pulse.value_or(GpioLine{}.pulse_ms)};
    return {};
}

Status read_profile_table(lua_State* L, Profile& p) {
    TableReader r(L, -1, p, "");
    std::optional<std::string> s;
    std::optional<double> d;
    TRY(take(r.string("description"), s));
    p.description = s.value_or("");
    TRY(take(r.string("clock"), s));
    if (s && *s != "virtual" && *s != "monotonic")
        return {ErrorCode::invalid_argument, r.at("clock") + " is '" + *s + "', expected 'virtual' or 'monotonic'"};
    p.virtual_clock = !s || *s == "virtual";
    for (auto [key, rate, what] : {std::tuple{"sample_rate_hz", &p.sample_rate_hz, "the sensors' sample rate in Hz"},
                                   std::tuple{"control_rate_hz", &p.control_rate_hz, "the control loop's rate in Hz"}}) {
        TRY(take(r.number(key), d));
        if (d) *rate = *d;
        if (!(*rate > 0))  // NaN too
            return {ErrorCode::invalid_argument, r.at(key) + " = " + format_param_value(*rate) + ": must be > 0 (" + what + ")"};
    }
    std::vector<std::string> list;
    TRY(take(r.string_list("plugin_path"), list));
    for (const auto& entry : list) {  // a mistyped folder would be searched, found empty, and the run go on
        p.plugin_path.push_back(fs::path(entry).is_absolute() ? fs::path(entry) : p.path.parent_path() / entry);
        if (std::error_code ec; !fs::is_directory(p.plugin_path.back(), ec))
            return {ErrorCode::invalid_argument, r.at("plugin_path") + ": " + p.plugin_path.back().string() + " is not a folder"};
    }
    TRY(take(r.string_list("record_joints"), p.record_joints));
    TRY(take(r.string_list("identification_channels"), p.identification_channels));

    TRY(r.each("devices", [&](const std::string& name, const std::string& path) -> Status {
        TableReader dr(L, -1, p, path);
        if (!lua_istable(L, -1)) return {ErrorCode::invalid_argument, dr.at("") + " must be a table { plugin = ..., params = {...} }"};
        DeviceSpec dev;
        dev.name = name;
        std::optional<std::string> plugin;
        TRY(take(dr.string("plugin"), plugin));
        if (!plugin) return {ErrorCode::invalid_argument, dr.at("plugin") + " is missing (which plugin drives it? `rollsense plugins` lists them)"};
        dev.plugin = *plugin;
        dr.push("params");
        auto params = lua_to_param_map(L, -1, dr.at("params"));
        lua_pop(L, 1);
        if (!params) return params.status();
        dev.params = std::move(*params);
        TRY(dr.reject_unknown());
        p.devices.push_back(std::move(dev));
        return {};
    }));
    TRY(r.each("joints", [&](const std::string& name, const std::string& path) -> Status {
        TableReader jr(L, -1, p, path);
        if (!lua_istable(L, -1)) return {ErrorCode::invalid_argument, jr.at("") + " must be a table { min = ..., max = ... }"};
        JointLimit j;
        j.name = name;
        std::optional<double> v;
        for (auto [key, bound] : {std::pair{"min", &j.min}, std::pair{"max", &j.max}}) {
            TRY(take(jr.number(key), v));
            if (!v) return {ErrorCode::invalid_argument, jr.at(key) + " is missing (the kernel keeps the joint within min and max)"};
            if (!std::isfinite(*v)) return {ErrorCode::invalid_argument, jr.at(key) + " is " + format_param_value(*v) + ", expected a finite number"};
            *bound = *v;
        }
        if (j.min >= j.max) return {ErrorCode::invalid_argument, jr.at("min") + " is not below its max, joints." + name + ".max (" + format_param_value(j.max) + ")"};
        for (auto [key, bound] : {std::pair{"max_velocity", &j.max_velocity}, std::pair{"max_current", &j.max_current}}) {
            TRY(take(jr.number(key), v));
            *bound = v.value_or(0);
            // Written so that NaN fails: it would switch a limit's check off (checked at load: `run --check` sees it).
            if (!(*bound >= 0 && *bound <= DBL_MAX))
                return {ErrorCode::invalid_argument, jr.at(key) + " is " + format_param_value(*bound) + ", expected a number >= 0"};
        }
        std::optional<std::string> safe;
        TRY(take(jr.string("safe"), safe));
        if (safe && *safe != "hold" && *safe != "torque_off")
            return {ErrorCode::invalid_argument, jr.at("safe") + " is '" + *safe + "', expected 'hold' or 'torque_off'"};
        j.safe_torque_off = safe && *safe == "torque_off";
        TRY(jr.reject_unknown());
        p.joints.push_back(j);
        return {};
    }));
    TRY(r.each("controllers", [&](const std::string& name, const std::string& path) -> Status {
        auto params = lua_to_param_map(L, -1, r.at(path));
        if (!params) return params.status();
        p.controllers.push_back({name, std::move(*params)});
        return {};
    }));
    int t = r.push("safety");
    if (t == LUA_TTABLE) {
        TableReader sr(L, -1, p, "safety");
        if (sr.push("estop") != LUA_TNIL) TRY(read_gpio(L, TableReader(L, -1, p, "safety.estop"), false, p.estop));
        lua_pop(L, 1);
        if (sr.push("trigger") != LUA_TNIL) TRY(read_gpio(L, TableReader(L, -1, p, "safety.trigger"), true, p.trigger));
        lua_pop(L, 1);
        TRY(sr.reject_unknown());
    } else if (t != LUA_TNIL) {
        lua_pop(L, 1);
        return {ErrorCode::invalid_argument, r.at("safety") + " must be a table"};
    }
    lua_pop(L, 1);
    return r.reject_unknown();
}

// Where each key of the table at the top is written (path → "file:line"), read in the text of the file whose
// constructor made the table it is in: an included table is in its own file, at paths from its top.
void note_sites(lua_State* L, const LoadState& st, const TableSource* src, std::string in_src, const std::string& path,
                int depth, std::map<std::string, std::string>& out) {
    if (auto it = st.sources.find(lua_topointer(L, -1)); it != st.sources.end()) src = &it->second, in_src.clear();
    for (lua_pushnil(L); lua_next(L, -2); lua_pop(L, 1)) {
        // Bounded: a table reached by many paths (itself, a shared one) would give paths without end.
        if (out.size() >= 10000) return lua_pop(L, 2);
        lua_pushvalue(L, -2);  // a copy: lua_tostring would turn a number key into a string under lua_next
        const std::string key = lua_tostring(L, -1) ? lua_tostring(L, -1) : "?";
        lua_pop(L, 1);
        if (key.size() > 256) continue;  // no key of a profile is that long: not worth a site
        auto now = lua_to_param(L, -1, path);
        out[path + key] = src->where(in_src + key, now ? &*now : nullptr);  // "": set later, not by that file
        if (lua_istable(L, -1) && depth < 8) note_sites(L, st, src, in_src + key + ".", path + key + ".", depth + 1, out);
    }
}

// Apply --set keys of the profile (sample_rate_hz=50, devices.tactile.params.x=1) to its table.
Status apply_dotted_settings(lua_State* L, const Settings& settings, const std::string& file) {
    for (const auto& [key, value] : settings.values()) {
        if (!is_profile_path(key)) continue;
        settings.mark_used(key);
        std::vector<std::string> parts;
        for (std::size_t start = 0, dot = 0; start <= key.size(); start = dot + 1) {
            dot = std::min(key.find('.', start), key.size());
            parts.push_back(key.substr(start, dot - start));
        }
        int top = lua_gettop(L);
        lua_pushvalue(L, -1);
        for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
            if (lua_getfield(L, -1, parts[i].c_str()) != LUA_TTABLE) {
                lua_settop(L, top);
                return {ErrorCode::invalid_argument,
                        "--set " + key + ": " + file + " has no table '" + parts[i] + "' on that path"};
            }
        }
        push_param(L, value);
        lua_setfield(L, -2, parts.back().c_str());
        lua_settop(L, top);
    }
    return {};
}

}  // namespace

Status profile_refusal(const Status& s, const Settings& settings) {
    if (s.code() != ErrorCode::invalid_argument) return s;
    for (const auto& [key, value] : settings.values())
        if (is_profile_path(key) && (s.message().find("'" + key.substr(key.rfind('.') + 1) + "'") != std::string::npos ||
                                     s.message().find(key) != std::string::npos))
            return Status{ErrorCode::bad_setting, "--set " + key + "=" + format_param_value(value) + ": " + s.message()};
    return Status{ErrorCode::bad_profile, s.message()};
}

Result<Profile> load_profile(const std::string& name_or_path, const fs::path& share_dir, const Settings& settings) {
    return load_profile(name_or_path, share_dir, settings, SandboxLimits{});
}

Result<Profile> load_profile(const std::string& name_or_path, const fs::path& share_dir, const Settings& settings,
                             const SandboxLimits& limits) {
    Profile p;
    p.path = resolve_profile_path(name_or_path, share_dir);
    p.name = p.path.stem().string();
    if (std::error_code ec; !fs::exists(p.path, ec))
        return Error{ErrorCode::not_found, profile_not_found(name_or_path, p.path, share_dir)};
    ProfileBudget budget;
    budget.heap.cap = limits.memory_bytes;
    budget.max_ms = limits.max_slice_ms;
    std::unique_ptr<lua_State, LuaCloser> holder(lua_newstate(&LuaHeap::allocate, &budget.heap));
    if (!holder) return Error{ErrorCode::io_error, "cannot create a Lua state for profile " + p.path.string()};
    lua_State* L = holder.get();
    budget.heap.running = L;  // a refusal notes the profile's line
    *static_cast<ProfileBudget**>(lua_getextraspace(L)) = &budget;
    lua_sethook(L, &budget_hook, LUA_MASKCOUNT, 10000);
    LoadState st{share_dir, &settings, 0, {}};
    lua_pushlightuserdata(L, &st);
    lua_pushcclosure(L, [](lua_State* L2) { return run_profile_file(L2, fs::path(lua_tostring(L2, 1))); }, 1);
    lua_pushstring(L, p.path.c_str());
    if (const int rc = lua_pcall(L, 1, 1, 0); rc != LUA_OK) {
        const char* msg = lua_tostring(L, -1);
        std::string text = msg ? msg : "(error object is not a string)";
        const char* at = budget.heap.refused_at.data();  // Lua's memory error has no place: the line the allocator noted
        if (rc == LUA_ERRMEM)
            text = (*at ? std::string(at) : p.path.string()) + ": " + text + " (the profile went past the memory cap of " +
                   std::to_string(limits.memory_bytes >> 20) + " MB; --memory-limit-mb)";
        return Error{ErrorCode::parse_error, "profile " + text};
    }
    if (auto s = apply_dotted_settings(L, settings, p.path.string()); !s.ok()) return s.error();
    note_sites(L, st, nullptr, "", "", 0, p.sites);  // the top table is in st.sources: its file returned it
    if (auto s = read_profile_table(L, p); !s.ok()) return s.error();
    return p;
}

}  // namespace rollsense::runtime
