// A ClassifierFactory backed by the kernel's plugin registry: every call
// validates the parameters against the plugin's schema, creates an instance
// through a lifecycle handle (which pins the plugin's library) and configures
// it. The returned pointer shares ownership of the handle, so the library
// stays loaded as long as the classifier lives.
#pragma once

#include <string>
#include <vector>

#include "analysis/learn/cross_validation.hpp"
#include "runtime/plugin/plugin_registry.hpp"

namespace rollsense::learn {

// The names of the classifier plugins the registry can load, sorted.
std::vector<std::string> available_classifiers(runtime::PluginRegistry& registry);
// Ok when `plugin` names a classifier plugin that loads; else the registry's refusal of its file, or "no classifier
// plugin named 'X'" with the classifier plugins there are (only those) and where they were looked for.
Status find_classifier_plugin(runtime::PluginRegistry& registry, const std::string& plugin);

// For `rollsense plugins --check`: what `plugin`, configured with its defaults, declares beyond its schema is
// consistent with it: its search space names only parameters of its schema (check_search_space). Its errors name the
// plugin; one whose defaults do not configure it (a required parameter) is not checked here: using it says why.
Status check_classifier_declarations(runtime::PluginRegistry& registry, const std::string& plugin);

// `registry` must outlive the factory. Fails at once, as find_classifier_plugin, if no classifier plugin named
// `plugin` loads.
Result<ClassifierFactory> plugin_classifier_factory(runtime::PluginRegistry& registry, const std::string& plugin,
                                                    PluginContext context = {});

}  // namespace rollsense::learn
