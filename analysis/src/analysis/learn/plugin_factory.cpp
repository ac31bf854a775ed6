#include "analysis/learn/plugin_factory.hpp"

#include <algorithm>

#include "analysis/learn/bayes_opt.hpp"
#include "analysis/learn/checked_classifier.hpp"

namespace rollsense::learn {

std::vector<std::string> available_classifiers(runtime::PluginRegistry& registry) {
    std::vector<std::string> names;
    for (const auto& c : registry.scan())
        if (c.library && c.library->manifest().kind == PluginKind::classifier) names.push_back(c.library->name());
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

Status find_classifier_plugin(runtime::PluginRegistry& registry, const std::string& plugin) {
    auto found = registry.find(plugin, PluginKind::classifier);
    if (found) return {};
    // A plugin of that name of another kind, or its own file refused: the registry's words say which (review:
    // "no classifier plugin named" hid a file another compiler built).
    const auto& found_files = registry.scan();
    if (std::ranges::any_of(found_files, [&](const auto& c) { return c.is_plugin(plugin); })) return found.error();
    const auto names = available_classifiers(registry);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    std::string where;
    for (const auto& d : registry.search_path()) where += (where.empty() ? "" : ", ") + d.string();
    return {ErrorCode::not_found, "no classifier plugin named '" + plugin + "'. Available classifier plugins: " +
                                      (list.empty() ? std::string("none") : list) + " (searched " + where +
                                      "; add a folder with --plugin-path, `rollsense plugins` lists what loads)"};
}

Result<ClassifierFactory> plugin_classifier_factory(runtime::PluginRegistry& registry, const std::string& plugin,
                                                    PluginContext context) {
    if (auto found = find_classifier_plugin(registry, plugin); !found) return found.error();
    auto lib = registry.find(plugin, PluginKind::classifier);
    if (!lib) return lib.error();
    auto schema = runtime::PluginRegistry::schema_of(**lib);
    if (!schema) return schema.error();
    if (context.instance.empty()) context.instance = "classifier";
    return ClassifierFactory([&registry, plugin, context, schema = *schema](const ParamSet& raw) -> Result<ClassifierPtr> {
        auto params = validate_params(schema, raw.values(), "classifier plugin '" + plugin + "'");
        if (!params) return params.error();
        auto handle = registry.create_classifier(plugin, context.instance);
        if (!handle) return handle.error();
        std::shared_ptr<runtime::ClassifierHandle> owner(std::move(handle).value());
        if (auto s = owner->configure(*params, context); !s) {
            // Its own defaults refused as a bad argument: the plugin's fault (exit 3), not the command line's (plugin
            // review: exit 2). Other failures (a missing file, a device) keep their own code.
            if (raw.values().empty() && s.code() == ErrorCode::invalid_argument)
                return Status{ErrorCode::plugin_error, s.message() + " (no parameter was given: the plugin refuses its "
                                                                     "own defaults)"};
            return s;
        }
        if (auto s = owner->activate(); !s) return s;
        // Written outside this repository: what it predicts is checked before use.
        return checked_classifier(ClassifierPtr(owner, &owner->plugin()), "classifier plugin '" + plugin + "'", schema);
    });
}

Status check_classifier_declarations(runtime::PluginRegistry& registry, const std::string& plugin) {
    auto factory = plugin_classifier_factory(registry, plugin);
    if (!factory) return factory.error();
    auto probe = (*factory)(ParamSet{});  // configured with its defaults, as the docs promise (user review: not said)
    if (!probe) return Status(probe.error()).with_context("configured with its defaults");
    // A space that depends on the shape is still checked whenever tuning asks for it.
    try {
        (*probe)->search_space(kProbeRows, kProbeCols);
    } catch (const StatusError& e) {
        return e.status();
    }
    return {};
}

}  // namespace rollsense::learn
