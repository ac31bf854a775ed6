// Declared script settings: what rs.settings{...} declares at the top of a
// script (or rs.settings("module", {...}) in a Lua module), how a --set value
// is checked against its declaration, and the text `rollsense run SCRIPT
// --help` prints. docs/scripting.md ("Settings") is the user's description.
//
//   rs.settings{
//     runs    = { default = 50, kind = "integer", min = 1, help = "repetitions of each object and speed" },
//     objects = { default = "C1,C2", kind = "objects", help = "catalogue ids, comma-separated" },
//   }
//
// A declaration is a ParamSpec (the SDK's parameter schema entry, so the
// types, ranges and their messages are the plugins' own) plus two kinds of
// text checked item by item: "object" (one id of the object catalogue),
// "objects" (comma-separated ids, as the scripts split them) and "numbers";
// the script reads such a value as checked: its items, one comma between
// them, no spaces.
#pragma once

#include <lua.hpp>

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rollsense/object_catalogue.hpp"
#include "rollsense/params.hpp"
#include "runtime/lua/sandbox.hpp"
#include "runtime/profile/profile.hpp"

namespace rollsense::script_settings {

enum class ListKind { none, object, objects, numbers };

struct Declaration {
    std::string key;          // as --set names it: "runs", "etroll.clamp_current"
    ParamSpec spec;           // type, default (nullopt: required), min/max, help in spec.doc
    ListKind list = ListKind::none;
    std::optional<ParamValue> fallback;  // the default exactly as the script wrote it
};

// The kinds a declaration may name, for messages.
inline constexpr const char* kKinds = "number, integer, boolean, string, object, objects, numbers";

// Reads the declaration table at `index` for namespace `ns` ("" for the
// script's own settings). A bad declaration raises a Lua error naming the
// setting and what is accepted.
std::vector<Declaration> read_declarations(lua_State* L, int index, const std::string& ns);

// A --set value checked against its declaration: the value to hand the
// script (a list's checked items joined by commas), or an error naming the setting, the value and what is accepted
// (for "objects": the catalogue's ids). `catalogue` may be null when no
// declaration needs it.
Result<ParamValue> check_value(const Declaration& d, const ParamValue& given, const ObjectCatalogue* catalogue,
                               bool is_default = false);  // the declaration's default, not a --set

// One rs.settings call as the script's top makes it: a module's (`ns` its name) or the script's own (`ns` empty).
struct SettingsCall {
    std::string ns;
    std::string where;                      // "demo.lua:5": its file:line, which the run's refusals name too
    std::vector<Declaration> declarations;  // in the order rs.settings checks them (by key)
};

// The --set values of `given` checked as a run checks them before its first trial, call by call in the order the
// script makes them (so that of two mistakes the same one is named first): a setting declared twice, a default of
// objects the catalogue lacks, each declared setting's value, a required one that is missing, and after each call
// every key nothing declared so far accounts for (unaccounted_key: all of them after the script's own call; those of
// its namespace after a module's), each refusal at its call's file:line. `given` as the profile left it: the keys it
// read are its own. For `rollsense run SCRIPT --check`, which runs no trial.
Status check_given(const std::vector<SettingsCall>& calls, const runtime::Settings& given,
                   const ObjectCatalogue* catalogue);

// Whether any declaration names catalogue objects (kind "object" or "objects"): then the catalogue is read.
bool names_objects(const std::vector<Declaration>& declared);

// A default of catalogue objects checked as a --set of them is: the script's mistake (rs.settings refuses it).
Status check_default(const Declaration& d, const ObjectCatalogue& catalogue);

// The first --set key of `given` that is no profile entry, was not read by the profile, and is not in `declared`;
// only keys of `only_namespace` when given (a module's rs.settings), every key for the script's own call.
std::optional<std::string> unaccounted_key(const runtime::Settings& given, const std::set<std::string>& declared,
                                           const std::string* only_namespace);

// "setting 'KEY' is required: pass --set KEY=VALUE (its help)".
std::string required_setting(const Declaration& d);

// "--set KEY: no such setting. Settings here: ..." with the way out; `known`: the declared keys, comma-separated.
std::string no_such_setting(const std::string& key, const std::string& known);

// The catalogue a run's objects come from: a device's 'catalogue' parameter (the sim sensor's), else the stock one.
std::filesystem::path catalogue_path(const runtime::Profile& profile, const std::filesystem::path& share_dir);

// One line per setting: "  runs=50   integer >= 1: repetitions of ...".
std::string describe(const std::vector<Declaration>& declarations);

// The settings a script declares, found without running it: its top is run
// with a stand-in rollsense module that records rs.settings declarations
// and stops at the first other rs.* call (that is where trials could begin;
// rs.on_cleanup only registers, and is passed), naming it in `stopped_at`
// ("demo.lua:9 (rs.trial)", empty if the top ran to its end).
// Its modules (require) load as in a run, so theirs are included.
// Under the run's limits (`limits`: --slice-limit-ms, --memory-limit-mb).
// All declarations by key; `calls`, if given, gets them call by call.
Result<std::vector<Declaration>> declared_by(const std::filesystem::path& script,
                                             const std::filesystem::path& share_dir,
                                             const runtime::SandboxLimits& limits, std::string* stopped_at = nullptr,
                                             std::vector<SettingsCall>* calls = nullptr);

}  // namespace rollsense::script_settings
