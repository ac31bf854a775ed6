#include "cli/run_check.hpp"

#include <cstdio>
#include <optional>

#include "analysis/lua/script_settings.hpp"
#include "cli/command.hpp"
#include "rollsense/object_catalogue.hpp"
#include "runtime/robot/robot.hpp"

namespace rollsense::cli {

int check_run_settings(const runtime::SessionOptions& o, const std::string& script_arg) {
    // In the run's order (the profile loads before the script), so that of two mistakes the run's first is named.
    const runtime::Settings settings = o.settings;  // the keys the profile reads are marked in it: its own
    auto profile = runtime::load_profile(o.profile, o.share_dir, settings, o.sandbox);
    if (!profile) throw StatusError(runtime::profile_refusal(profile.status(), o.settings));
    // Each device's plugin found and its parameters checked against its schema, as the run's first step with the
    // devices; configuring them (opening a port, asking a servo) is the run's.
    auto search = o.plugin_path;
    search.insert(search.end(), profile->plugin_path.begin(), profile->plugin_path.end());
    runtime::PluginRegistry registry(runtime::PluginRegistry::default_search_path(search));
    for (const auto& device : profile->devices)
        if (auto resolved = runtime::resolve_device(*profile, device, registry); !resolved)
            throw StatusError(runtime::profile_refusal(resolved.status(), o.settings));
    std::string stopped_at;
    std::vector<script_settings::SettingsCall> calls;
    auto declared = script_settings::declared_by(o.script, o.share_dir, o.sandbox, &stopped_at, &calls);
    if (!declared) throw StatusError(Status{declared.error()});
    std::optional<ObjectCatalogue> catalogue;
    if (script_settings::names_objects(*declared)) {
        auto loaded = ObjectCatalogue::load(script_settings::catalogue_path(*profile, o.share_dir));
        if (!loaded) throw StatusError(Status{loaded.error()});
        catalogue = std::move(*loaded);
    }
    if (auto s = script_settings::check_given(calls, settings, catalogue ? &*catalogue : nullptr); !s.ok())
        throw StatusError(s);
    if (declared->empty())
        std::printf("%s declares no settings%s: its --set keys are checked only when it runs; profile '%s' loads\n",
                    script_arg.c_str(), stopped_at.empty() ? "" : (" before " + stopped_at).c_str(),
                    o.profile.c_str());
    else
        std::printf("%s: %zu settings checked with the --set given, profile '%s' loads with its %zu devices' plugins and "
                    "parameters; no trial was run\n",
                    script_arg.c_str(), declared->size(), o.profile.c_str(), profile->devices.size());
    return kExitOk;
}

}  // namespace rollsense::cli
