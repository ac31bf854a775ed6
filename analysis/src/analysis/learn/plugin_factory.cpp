#include "analysis/learn/plugin_factory.hpp"

#include "analysis/learn/checked_classifier.hpp"

namespace rollsense::learn {

Result<ClassifierFactory> plugin_classifier_factory(runtime::PluginRegistry& registry, const std::string& plugin,
                                                    PluginContext context) {
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
        if (auto s = owner->configure(*params, context); !s) return s;
        if (auto s = owner->activate(); !s) return s;
        // Written outside this repository: what it predicts is checked before use.
        return checked_classifier(ClassifierPtr(owner, &owner->plugin()), "classifier plugin '" + plugin + "'");
    });
}

}  // namespace rollsense::learn
