// The plugin manifest: the one symbol a rollsense plugin library exports.
//
// A plugin library defines its class and one line:
//
//     ROLLSENSE_PLUGIN(MySensor, sensor, "my_sensor", "1.0.0",
//                      "What it measures, in one line", my_sensor_schema)
//
// which exports `rollsense_plugin_manifest` (through BOOST_DLL_ALIAS). The kernel reads the manifest's first fields
// (magic, ABI version, compiler tag) before touching anything else, so a library built against another SDK is reported
// as "ABI mismatch" instead of crashing the loader.
#pragma once

#include <cstdint>

#include <boost/dll/alias.hpp>

#include "rollsense/actuator.hpp"
#include "rollsense/classifier.hpp"
#include "rollsense/export.hpp"
#include "rollsense/params.hpp"
#include "rollsense/sensor.hpp"

namespace rollsense {

// Bump whenever a type in kernel/include/rollsense changes layout or a virtual function is added, removed or reordered.
inline constexpr std::uint32_t kPluginAbiVersion = 1;
inline constexpr std::uint32_t kPluginMagic = 0x4c505352;  // "RSPL"
inline constexpr const char* kPluginManifestSymbol = "rollsense_plugin_manifest";

#define ROLLSENSE_STRINGIFY_IMPL(x) #x
#define ROLLSENSE_STRINGIFY(x) ROLLSENSE_STRINGIFY_IMPL(x)
// Plugins and kernel must agree on the C++ ABI, not just on our headers: the compiler, the string ABI, and libstdc++'s
// debug mode (-D_GLIBCXX_DEBUG lays its containers out otherwise: a plugin built so crashed the program).
#ifdef _GLIBCXX_DEBUG
#define ROLLSENSE_STDLIB_MODE "-glibcxxdebug"
#else
#define ROLLSENSE_STDLIB_MODE ""
#endif
#define ROLLSENSE_COMPILER_TAG \
    "gcc-" __VERSION__ "-cxx11abi" ROLLSENSE_STRINGIFY(_GLIBCXX_USE_CXX11_ABI) ROLLSENSE_STDLIB_MODE

enum class PluginKind : std::uint32_t { sensor = 1, actuator = 2, classifier = 3 };

std::string_view to_string(PluginKind kind) noexcept;

// Standard layout; the first three fields never move.
struct PluginManifest {
    std::uint32_t magic;
    std::uint32_t abi_version;
    const char* compiler_tag;
    // -- valid only when the three fields above match the kernel's --
    const char* name;
    PluginKind kind;
    const char* version;
    const char* description;
    ParamSchema (*schema)();
    // Exactly one of these is set, the one matching `kind`. Typed factories (rather than one returning Component*)
    // avoid dynamic_cast across libraries.
    Sensor* (*create_sensor)();
    Actuator* (*create_actuator)();
    Classifier* (*create_classifier)();
    void (*destroy)(Component*) noexcept;
};

using PluginManifestFn = const PluginManifest*();

namespace detail {
template <class Base, class T>
Base* make() { if constexpr (std::is_base_of_v<Base, T>) return new T(); else return nullptr; }
template <class Base, class T>  // interface Base's factory: nullptr for a class of another kind
constexpr Base* (*factory)() = std::is_base_of_v<Base, T> ? &make<Base, T> : nullptr;
template <class T>
constexpr bool of_kind(PluginKind k) {
    return k == PluginKind::sensor     ? std::is_base_of_v<Sensor, T>
           : k == PluginKind::actuator ? std::is_base_of_v<Actuator, T> : std::is_base_of_v<Classifier, T>;
}
template <class T>
void destroy(Component* c) noexcept { delete static_cast<T*>(c); }
}  // namespace detail

}  // namespace rollsense

// KIND is one of: sensor, actuator, classifier. SCHEMA_FN is a function `rollsense::ParamSchema fn()` listing the
// plugin's parameters.
#define ROLLSENSE_PLUGIN(CLASS, KIND, NAME, VERSION, DESCRIPTION, SCHEMA_FN)                                  \
    static_assert(::rollsense::detail::of_kind<CLASS>(::rollsense::PluginKind::KIND),                        \
                  "the plugin class must derive from its KIND's interface: Sensor, Actuator or Classifier");    \
    namespace {                                                                                             \
    const ::rollsense::PluginManifest* rollsense_manifest_impl() {                                          \
        static const ::rollsense::PluginManifest manifest{                                                  \
            ::rollsense::kPluginMagic,                                                                      \
            ::rollsense::kPluginAbiVersion,                                                                 \
            ROLLSENSE_COMPILER_TAG,                                                                         \
            NAME,                                                                                           \
            ::rollsense::PluginKind::KIND,                                                                  \
            VERSION,                                                                                        \
            DESCRIPTION,                                                                                    \
            &SCHEMA_FN,                                                                                     \
            ::rollsense::detail::factory<::rollsense::Sensor, CLASS>,                                          \
            ::rollsense::detail::factory<::rollsense::Actuator, CLASS>,                                        \
            ::rollsense::detail::factory<::rollsense::Classifier, CLASS>,                                      \
            &::rollsense::detail::destroy<CLASS>,                                                           \
        };                                                                                                  \
        return &manifest;                                                                                   \
    }                                                                                                       \
    }                                                                                                       \
    BOOST_DLL_ALIAS(rollsense_manifest_impl, rollsense_plugin_manifest)
