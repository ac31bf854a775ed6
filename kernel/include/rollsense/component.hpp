// The lifecycle every plugin instance goes through.
//
//   unconfigured --configure--> inactive --activate--> active
//        ^                         |  ^                   |
//        +--------cleanup----------+  +----deactivate-----+
//
//   any hook that fails or throws --> error --recover--> unconfigured
//
// A plugin only fills the hooks. The kernel's handle (kernel/src/runtime/plugin/component_handle) owns the state
// machine: it refuses illegal transitions, catches every exception a hook throws and turns it into a typed error
// naming the plugin, and moves the component to `error`, from which `recover` brings it back without reloading
// anything (the complaint about ros2_control's one-way error state).
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "rollsense/export.hpp"
#include "rollsense/params.hpp"
#include "rollsense/status.hpp"

namespace rollsense {

enum class LifecycleState { unconfigured, inactive, active, error };

std::string_view to_string(LifecycleState state) noexcept;

// What the kernel tells a plugin instance about where it runs.
struct PluginContext {
    std::string instance;                // the device name in the profile, e.g. "tactile"
    std::filesystem::path share_dir;     // read-only data: object catalogue, profiles, Lua modules
    std::filesystem::path profile_path;  // the profile this instance comes from (may be empty)
    bool virtual_time = false;           // true: time only advances when the scheduler says so
};

using ValueMap = std::map<std::string, ParamValue>;

class ROLLSENSE_API Component {
public:
    virtual ~Component() = default;

    // Parameters arrive validated against the plugin's schema, defaults filled in.
    virtual Status on_configure(const ParamSet& params, const PluginContext& context) {
        (void)params;
        (void)context;
        return {};
    }
    virtual Status on_activate() { return {}; }
    virtual Status on_deactivate() { return {}; }
    virtual Status on_cleanup() { return {}; }
    // Called on `recover` from the error state: release whatever the failure left behind (close a bus, forget a
    // half-read frame). Success returns the component to `unconfigured`.
    virtual Status on_recover() { return {}; }

    // A plugin-specific operation reachable from Lua as `device:call(verb, args)`,
    // e.g. a replay sensor's "select". Unknown verbs return ErrorCode::unsupported.
    virtual Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) {
        (void)args;
        return Error{ErrorCode::unsupported, "no operation '" + verb + "'"};
    }
};

}  // namespace rollsense
