// rs.settings{...} / rs.settings("module", {...}): a script or module declares
// its settings, so that every --set is checked before the first trial: the
// values against their declarations (types, ranges, catalogue objects, and a
// default of objects against the catalogue too), and, in the script's own
// call, every --set key against what is declared (docs/scripting.md,
// "Settings"). The kernel's rs.setting then refuses an undeclared key of a
// declaring namespace. Registered into the kernel's Lua module as an
// extension, beside rs.analyse: the object catalogue is not the kernel's
// business.
#include <optional>
#include <set>

#include "analysis/lua/script_settings.hpp"
#include "runtime/lua/api_internal.hpp"

namespace rollsense::runtime::lua_api {
namespace {

using script_settings::Declaration;

// A bad declaration: the script's error.
[[noreturn]] void refuse(lua_State* L, const std::string& message) {
    raise_status(L, Status{ErrorCode::invalid_argument, message});
}

// A --set the declarations refuse (or a required one not given): the command
// line's error (exit 2), raised where the script or module declared it (file:line).
[[noreturn]] void refuse_set(lua_State* L, const std::string& message) {
    raise_status(L, Status{ErrorCode::bad_setting, message});
}

std::string known_settings(const Settings& st) {
    std::string names;
    for (const auto& [k, v] : st.declared()) names += (names.empty() ? "" : ", ") + k;
    return names;
}

int l_settings(lua_State* L) {
    Session& s = Session::of(L);
    const bool module = lua_type(L, 1) == LUA_TSTRING;
    const std::string ns = module ? lua_tostring(L, 1) : "";
    if (module && (ns.empty() || ns.find('.') != std::string::npos || is_profile_path(ns + ".x")))
        refuse(L, "rs.settings('" + ns + "', {...}): a module's settings live under one plain name that is not a "
                  "profile entry (devices, joints, ...); use the module's name, e.g. rs.settings('etroll', {...})");
    // User review: declared after a trial, a bad --set was refused only then, trials on disk and the bad value in
    // run-config.csv, so that no resume could continue them.
    if (const auto& begun = s.recorder().trial(); !begun.id.empty())
        refuse(L, "rs.settings: declared after a trial began ('" + begun.id + "'): a --set is checked before the first "
                  "trial only if its setting is declared before it; move this rs.settings (or the require of the "
                  "module that declares it) above the first rs.trial");
    const auto declarations = script_settings::read_declarations(L, module ? 2 : 1, ns);
    Settings& st = s.settings();

    std::optional<ObjectCatalogue> catalogue;
    if (script_settings::names_objects(declarations)) {
        auto loaded = ObjectCatalogue::load(script_settings::catalogue_path(s.profile(), s.options().share_dir));
        if (!loaded) raise_status(L, Status{loaded.error()}.with_context("rs.settings: kind 'objects'"));
        catalogue = std::move(*loaded);
    }
    for (const auto& d : declarations) {
        if (st.declared().count(d.key)) refuse(L, "rs.settings: " + d.key + " is declared twice");
        // A default of catalogue objects is checked as a --set of them is (check_value), whether or not a --set
        // overrides it: the script's mistake, refused before any trial (user review: it failed mid-run at the
        // unknown object, and offered a --resume that the fix, an edit of the script, makes impossible).
        if (d.fallback && catalogue && d.list != script_settings::ListKind::none)
            if (auto ok = script_settings::check_default(d, *catalogue); !ok.ok()) refuse(L, ok.message());
        const auto given = st.values().find(d.key);
        if (given == st.values().end()) {
            if (!d.fallback) refuse_set(L, script_settings::required_setting(d));
            st.declare(d.key, *d.fallback);
            continue;
        }
        auto value = script_settings::check_value(d, given->second, catalogue ? &*catalogue : nullptr);
        if (!value) refuse_set(L, value.error().message);
        st.declare(d.key, *value);
        st.set(d.key, *value);
    }
    // Every --set must mean something: in a module's call, those of its
    // namespace; in the script's, all (its modules have declared by now).
    std::set<std::string> declared;
    for (const auto& [key, value] : st.declared()) declared.insert(key);
    if (const auto stray = script_settings::unaccounted_key(st, declared, module ? &ns : nullptr))
        refuse_set(L, script_settings::no_such_setting(*stray, known_settings(st)));
    return 0;
}

void register_settings(lua_State* L) {
    lua_pushcfunction(L, l_settings);
    lua_setfield(L, -2, "settings");
}

const ExtraRegistration registration{&register_settings};

}  // namespace
}  // namespace rollsense::runtime::lua_api
