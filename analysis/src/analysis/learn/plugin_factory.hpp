// A ClassifierFactory backed by the kernel's plugin registry: every call
// validates the parameters against the plugin's schema, creates an instance
// through a lifecycle handle (which pins the plugin's library) and configures
// it. The returned pointer shares ownership of the handle, so the library
// stays loaded as long as the classifier lives.
#pragma once

#include <string>

#include "analysis/learn/cross_validation.hpp"
#include "runtime/plugin/plugin_registry.hpp"

namespace rollsense::learn {

// `registry` must outlive the factory. Fails at once if no classifier plugin
// named `plugin` is found (the error lists where the registry looked).
Result<ClassifierFactory> plugin_classifier_factory(runtime::PluginRegistry& registry, const std::string& plugin,
                                                    PluginContext context = {});

}  // namespace rollsense::learn
