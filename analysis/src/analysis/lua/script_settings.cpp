#include "analysis/lua/script_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "rollsense/csv.hpp"
#include "runtime/lua/api_internal.hpp"
#include "runtime/lua/lua_values.hpp"
#include "runtime/lua/sandbox.hpp"

namespace rollsense::script_settings {
namespace {

std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : text + ",") {
        if (c == ',' || c == ' ' || c == '\t') {
            if (!cur.empty()) out.push_back(cur);
            cur.clear();
        } else {
            cur.push_back(c);
        }
    }
    return out;
}

// A value as the user would type it after `--set key=`.
std::string typed_text(const ParamValue& v) {
    if (auto* s = std::get_if<std::string>(&v)) return *s;
    return format_param_value(v);
}

std::string range_text(const ParamSpec& s) {
    if (s.min && s.max) return " " + csv::format_number(*s.min) + ".." + csv::format_number(*s.max);
    if (s.min) return " >= " + csv::format_number(*s.min);
    if (s.max) return " <= " + csv::format_number(*s.max);
    return "";
}

std::string kind_text(const Declaration& d) {
    switch (d.list) {
        case ListKind::object: return "object (a catalogue id)";
        case ListKind::objects: return "objects (catalogue ids, comma-separated)";
        case ListKind::numbers: return "numbers (comma-separated)" + range_text(d.spec);
        case ListKind::none: break;
    }
    std::string choices;
    for (const auto& c : d.spec.choices) choices += (choices.empty() ? ", one of: " : ", ") + c;
    return std::string(to_string(d.spec.type)) + range_text(d.spec) + choices;
}

void set_kind(lua_State* L, Declaration& d, const std::string& kind) {
    if (kind == "number") d.spec.type = ParamType::number;
    else if (kind == "integer") d.spec.type = ParamType::integer;
    else if (kind == "boolean") d.spec.type = ParamType::boolean;
    else if (kind == "string") d.spec.type = ParamType::string;
    else if (kind == "object") d.spec.type = ParamType::string, d.list = ListKind::object;
    else if (kind == "objects") d.spec.type = ParamType::string, d.list = ListKind::objects;
    else if (kind == "numbers") d.spec.type = ParamType::string, d.list = ListKind::numbers;
    else luaL_error(L, "rs.settings: %s: kind '%s' is not one of: %s", d.key.c_str(), kind.c_str(), kKinds);
}

}  // namespace

std::vector<Declaration> read_declarations(lua_State* L, int index, const std::string& ns) {
    luaL_checktype(L, index, LUA_TTABLE);
    index = lua_absindex(L, index);
    std::vector<Declaration> out;
    for (lua_pushnil(L); lua_next(L, index); lua_pop(L, 1)) {
        if (lua_type(L, -2) != LUA_TSTRING) luaL_error(L, "rs.settings: the keys are setting names (strings)");
        Declaration d;
        d.key = (ns.empty() ? "" : ns + ".") + lua_tostring(L, -2);
        d.spec.name = d.key;
        if (!lua_istable(L, -1))
            luaL_error(L, "rs.settings: %s must be a table { default = ..., kind = ..., help = ... }", d.key.c_str());
        const std::string call = "rs.settings: " + d.key;
        runtime::lua_api::check_options(L, -1, call.c_str(), {"default", "kind", "min", "max", "help", "choices"});
        const int entry = lua_absindex(L, -1);
        lua_getfield(L, entry, "default");
        if (!lua_isnil(L, -1)) {
            auto v = runtime::lua_to_param(L, -1, call + ".default");
            if (!v) luaL_error(L, "%s", v.status().message().c_str());
            d.fallback = *v;
        }
        lua_pop(L, 1);
        const std::string kind = runtime::lua_api::opt_field_string(L, entry, "kind", "");
        if (!kind.empty()) {
            set_kind(L, d, kind);
        } else if (!d.fallback) {
            luaL_error(L, "rs.settings: %s needs a default or a kind (%s)", d.key.c_str(), kKinds);
        } else if (std::holds_alternative<bool>(*d.fallback)) {
            d.spec.type = ParamType::boolean;
        } else if (std::holds_alternative<std::string>(*d.fallback)) {
            d.spec.type = ParamType::string;
        } else if (!std::holds_alternative<std::int64_t>(*d.fallback) && !std::holds_alternative<double>(*d.fallback)) {
            luaL_error(L, "rs.settings: %s: the default must be a number, boolean or string", d.key.c_str());
        }
        lua_getfield(L, entry, "min");
        if (!lua_isnil(L, -1)) d.spec.min = luaL_checknumber(L, -1);
        lua_getfield(L, entry, "max");
        if (!lua_isnil(L, -1)) d.spec.max = luaL_checknumber(L, -1);
        for (auto bound : {d.spec.min, d.spec.max})
            if (bound && !std::isfinite(*bound))
                luaL_error(L, "rs.settings: %s: min and max must be finite numbers (leave one out for no bound)",
                           d.key.c_str());
        lua_pop(L, 2);
        // choices: the words a string takes (user review: a mode word was checked only by the analysis, after every
        // trial was recorded).
        lua_getfield(L, entry, "choices");
        if (!lua_isnil(L, -1)) {
            bool valid = d.spec.type == ParamType::string && d.list == ListKind::none && lua_istable(L, -1) &&
                         lua_rawlen(L, -1) > 0;
            for (lua_Integer i = 1; valid && i <= static_cast<lua_Integer>(lua_rawlen(L, -1)); ++i) {
                lua_rawgeti(L, -1, i);
                valid = lua_type(L, -1) == LUA_TSTRING;
                if (valid) d.spec.choices.emplace_back(lua_tostring(L, -1));
                lua_pop(L, 1);
            }
            if (!valid)
                luaL_error(L, "rs.settings: %s: choices must be a list of strings, e.g. choices = {\"fast\", \"slow\"}, "
                              "of a setting of kind 'string'", d.key.c_str());
        }
        lua_pop(L, 1);
        d.spec.doc = runtime::lua_api::opt_field_string(L, entry, "help", "");
        if (d.fallback) {
            auto ok = check_value(d, *d.fallback, nullptr, true);
            if (!ok)
                luaL_error(L, "rs.settings: %s: the default does not fit the declaration: %s", d.key.c_str(),
                           ok.status().message().c_str());
            if (d.list != ListKind::none) d.fallback = *ok;  // a list's items as checked: "C1,C2" for " C1, C2"
        }
        out.push_back(std::move(d));
    }
    std::sort(out.begin(), out.end(), [](const Declaration& a, const Declaration& b) { return a.key < b.key; });
    return out;
}

Result<ParamValue> check_value(const Declaration& d, const ParamValue& given, const ObjectCatalogue* catalogue,
                               bool is_default) {
    // Review: a declaration's own default was blamed on a --set nobody gave.
    const std::string where = (is_default ? "default " : "--set " + d.key + "=") + typed_text(given);
    const std::string about = d.spec.doc.empty() ? "" : " (" + d.key + ": " + d.spec.doc + ")";
    // A string setting takes any text, numbers included (--set model=2026.rsm).
    const ParamValue value = d.spec.type == ParamType::string ? ParamValue{typed_text(given)} : given;
    if (d.list != ListKind::none) {
        const auto items = split_list(std::get<std::string>(value));
        if (items.empty()) return Error{ErrorCode::invalid_argument, where + ": give at least one item" + about};
        if (d.list == ListKind::object && items.size() != 1)
            return Error{ErrorCode::invalid_argument, where + ": give one object" + about};
        for (const auto& item : items) {
            // An object twice names its trials twice (second diff review: C1,C1 recorded 3 trials, "3 already on disk").
            if (d.list == ListKind::objects && std::count(items.begin(), items.end(), item) > 1)
                return Error{ErrorCode::invalid_argument, where + ": '" + item + "' is listed twice; list each object "
                                                                  "once" + about};
            if (d.list != ListKind::numbers && catalogue && !catalogue->find(item))
                return Error{ErrorCode::invalid_argument,
                             where + ": '" + item + "' is not an object of " + catalogue->path().string() +
                                 " (objects: " + catalogue->ids() + ")"};
            if (d.list != ListKind::numbers) continue;
            auto n = csv::parse_number(item, d.key);
            // A declared range takes finite numbers only, as a single number's (validate_params).
            const bool ranged = d.spec.min || d.spec.max;
            const bool in_range = n && (!ranged || std::isfinite(*n)) && (!d.spec.min || *n >= *d.spec.min) &&
                                  (!d.spec.max || *n <= *d.spec.max);
            if (!in_range)
                return Error{ErrorCode::invalid_argument, where + ": '" + item + "' is not a number" +
                                                              range_text(d.spec) + about};
        }
        // The script reads the items that were checked, one comma between them and no space, as a list in
        // braces drops the spaces around its items (user review: --set 'objects= C1' passed, and the trial id
        // made of ' C1' was refused mid-run).
        std::string checked;
        for (const auto& item : items) checked += (checked.empty() ? "" : ",") + item;
        return ParamValue{checked};
    }
    ParamSpec spec = d.spec;
    spec.default_value.reset();
    const std::string context = is_default ? "the default" : "--set";
    auto checked = validate_params({spec}, {{d.key, value}}, context);
    if (!checked) {
        // validate_params names a plugin parameter ("--set: key 'runs': 0 is outside ..."); a setting is named as the
        // user typed it ("--set runs=0: 0 is outside ...", user review).
        std::string why = checked.error().message;
        const std::string named = context + ": key '" + d.key + "'";
        if (why.starts_with(named)) why = where + ": " + why.substr(why.compare(named.size(), 2, ": ") == 0 ? named.size() + 2 : named.size() + 1);
        return Error{ErrorCode::invalid_argument, why + about};
    }
    // A number keeps the type it was given in (150 stays a Lua integer, as the default would be).
    if (d.spec.type == ParamType::number) return value;
    return checked->values().at(d.key);
}

Status check_given(const std::vector<SettingsCall>& calls, const runtime::Settings& given,
                   const ObjectCatalogue* catalogue) {
    std::set<std::string> keys;  // declared so far
    for (const auto& call : calls) {
        const auto refuse = [&](ErrorCode code, const std::string& text) { return Status{code, call.where + ": " + text}; };
        for (const auto& d : call.declarations) {
            if (!keys.insert(d.key).second) return refuse(ErrorCode::invalid_argument, "rs.settings: " + d.key + " is declared twice");
            if (d.fallback && catalogue && d.list != ListKind::none)
                if (auto s = check_default(d, *catalogue); !s.ok()) return refuse(s.code(), s.message());
            const auto value = given.values().find(d.key);
            if (value == given.values().end()) {
                if (!d.fallback) return refuse(ErrorCode::bad_setting, required_setting(d));
                continue;
            }
            if (auto ok = check_value(d, value->second, catalogue); !ok) return refuse(ErrorCode::bad_setting, ok.error().message);
        }
        // The script's own rs.settings accounts for every key; a module's only for its namespace.
        if (const auto stray = unaccounted_key(given, keys, call.ns.empty() ? nullptr : &call.ns)) {
            std::string known;
            for (const auto& k : keys) known += (known.empty() ? "" : ", ") + k;
            return refuse(ErrorCode::bad_setting, no_such_setting(*stray, known));
        }
    }
    return {};
}

bool names_objects(const std::vector<Declaration>& declared) {
    return std::any_of(declared.begin(), declared.end(), [](const Declaration& d) {
        return d.list == ListKind::object || d.list == ListKind::objects;
    });
}

Status check_default(const Declaration& d, const ObjectCatalogue& catalogue) {
    if (auto ok = check_value(d, *d.fallback, &catalogue, true); !ok)
        return {ErrorCode::invalid_argument, "rs.settings: " + d.key + ": the default does not fit the declaration: " +
                                                 ok.error().message + "; edit the default in the script"};
    return {};
}

std::optional<std::string> unaccounted_key(const runtime::Settings& given, const std::set<std::string>& declared,
                                           const std::string* only_namespace) {
    for (const auto& [key, value] : given.values()) {
        if (runtime::is_profile_path(key) || given.used(key) || declared.count(key)) continue;
        if (only_namespace && runtime::setting_namespace(key) != *only_namespace) continue;
        return key;
    }
    return std::nullopt;
}

std::string required_setting(const Declaration& d) {
    return "setting '" + d.key + "' is required: pass --set " + d.key + "=VALUE" +
           (d.spec.doc.empty() ? "" : " (" + d.spec.doc + ")");
}

std::string no_such_setting(const std::string& key, const std::string& known) {
    return "--set " + key + ": no such setting. Settings here: " + known +
           "; a profile entry is overridden by its path, e.g. devices.NAME.params.KEY "
           "(rollsense run SCRIPT --help lists them; docs/scripting.md, Settings)";
}

std::filesystem::path catalogue_path(const runtime::Profile& profile, const std::filesystem::path& share_dir) {
    for (const auto& device : profile.devices)
        if (auto it = device.params.find("catalogue"); it != device.params.end())
            if (auto* text = std::get_if<std::string>(&it->second)) {
                std::filesystem::path p(*text);
                return p.is_relative() ? share_dir / p : p;
            }
    return share_dir / kStockCatalogue;
}

std::string describe(const std::vector<Declaration>& declarations) {
    std::size_t width = 0;
    std::vector<std::string> heads;
    for (const auto& d : declarations) {
        heads.push_back(d.key + "=" + (d.fallback ? typed_text(*d.fallback) : "(required)"));
        width = std::max(width, heads.back().size());
    }
    std::string out;
    for (std::size_t i = 0; i < declarations.size(); ++i) {
        const auto& d = declarations[i];
        out += "  " + heads[i] + std::string(width - heads[i].size() + 2, ' ') + kind_text(d) +
               (d.spec.doc.empty() ? "" : ": " + d.spec.doc) + "\n";
    }
    return out;
}

// ----------------------------------------------------------------- probe --
namespace {

struct Probe {
    std::vector<Declaration> found;
    std::vector<SettingsCall> calls;
    std::string stopped_at;  // "demo.lua:7 (rs.trial)": the call the probe stopped at
    runtime::Sandbox* sandbox = nullptr;
};

Probe& probe_of(lua_State* L) { return *static_cast<Probe*>(lua_touserdata(L, lua_upvalueindex(1))); }

// A cancel, not a plain error: a script's pcall around rs.trial would catch that and run on (into a loop of
// pcall(rs.wait, ...) until the slice limit, or past declarations that are not the run's first ones).
int stop_at(lua_State* L, const std::string& call) {
    auto& probe = probe_of(L);
    probe.stopped_at = std::string(runtime::script_line(L, 1).data()) + " (" + call + ")";
    probe.sandbox->cancel("the settings were read up to " + probe.stopped_at);
    probe.sandbox->arm(L);  // raised again at the next instruction, not the next hook period
    return luaL_error(L, "%s", probe.sandbox->cancel_reason().c_str());
}

int probe_stop(lua_State* L) { return stop_at(L, std::string("rs.") + lua_tostring(L, lua_upvalueindex(2))); }

int probe_settings(lua_State* L) {
    const bool module = lua_type(L, 1) == LUA_TSTRING;
    const std::string ns = module ? lua_tostring(L, 1) : "";
    auto found = read_declarations(L, module ? 2 : 1, ns);
    auto& probe = probe_of(L);
    probe.found.insert(probe.found.end(), found.begin(), found.end());
    probe.calls.push_back({ns, runtime::script_line(L, 1).data(), std::move(found)});
    return 0;
}

// rs.setting while probing: the declared default (what a run without --set reads).
int probe_setting(lua_State* L) {
    const std::string key = luaL_checkstring(L, 1);
    bool declared = false;
    for (const auto& d : probe_of(L).found) {
        if (d.key == key && d.fallback) {
            runtime::push_param(L, *d.fallback);
            return 1;
        }
        declared = declared || d.key == key;
    }
    // A required setting: no value to go on with while reading.
    if (lua_gettop(L) < 2)
        return stop_at(L, "rs.setting '" + key + "'" + (declared ? ", required" : " without a default"));
    lua_settop(L, 2);
    return 1;
}

// Any other rs.* field: a function that stops the probe, naming itself and its
// line; rs.on_cleanup only registers a function (scripts call it first), so it
// does nothing here.
int probe_index(lua_State* L) {
    if (lua_type(L, 2) == LUA_TSTRING && std::string_view(lua_tostring(L, 2)) == "on_cleanup") {
        lua_pushcfunction(L, [](lua_State*) { return 0; });
        return 1;
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    luaL_tolstring(L, 2, nullptr);  // the field's name
    lua_pushcclosure(L, probe_stop, 2);
    return 1;
}

}  // namespace

Result<std::vector<Declaration>> declared_by(const std::filesystem::path& script,
                                             const std::filesystem::path& share_dir,
                                             const runtime::SandboxLimits& limits, std::string* stopped_at,
                                             std::vector<SettingsCall>* calls) {
    Probe probe;
    runtime::Sandbox sandbox(limits,
                             {script.parent_path().empty() ? std::filesystem::path(".") : script.parent_path(),
                              share_dir / "lua"});
    probe.sandbox = &sandbox;
    lua_State* L = sandbox.state();
    lua_newtable(L);
    lua_pushlightuserdata(L, &probe);
    lua_pushcclosure(L, probe_settings, 1);
    lua_setfield(L, -2, "settings");
    lua_pushlightuserdata(L, &probe);
    lua_pushcclosure(L, probe_setting, 1);
    lua_setfield(L, -2, "setting");
    lua_newtable(L);
    lua_pushlightuserdata(L, &probe);
    lua_pushcclosure(L, probe_index, 1);
    lua_setfield(L, -2, "__index");
    lua_setmetatable(L, -2);
    sandbox.set_api_module(luaL_ref(L, LUA_REGISTRYINDEX));
    if (auto s = sandbox.load_file(script); !s.ok()) return s.error();
    sandbox.start_slice(L);
    if (const int rc = lua_pcall(L, 0, 0, 0); rc != LUA_OK && probe.stopped_at.empty()) {
        const char* msg = lua_tostring(L, -1);
        std::string text = msg ? msg : "(error object is not a string)";
        if (rc == LUA_ERRMEM) text = sandbox.memory_error(" while its settings were read");  // Lua's text has no place
        return Error{ErrorCode::invalid_argument, text};
    }
    std::sort(probe.found.begin(), probe.found.end(),
              [](const Declaration& a, const Declaration& b) { return a.key < b.key; });
    if (stopped_at) *stopped_at = probe.stopped_at;
    if (calls) *calls = std::move(probe.calls);
    return probe.found;
}

}  // namespace rollsense::script_settings
