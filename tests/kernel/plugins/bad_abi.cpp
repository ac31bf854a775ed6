// A library whose manifest claims another plugin ABI: the loader must report
// "ABI mismatch" without touching anything past the header.
#include <boost/dll/alias.hpp>

#include "rollsense/plugin.hpp"

namespace {
const rollsense::PluginManifest* manifest() {
    static const rollsense::PluginManifest m{rollsense::kPluginMagic, rollsense::kPluginAbiVersion + 41,
                                             ROLLSENSE_COMPILER_TAG, "test_bad_abi", rollsense::PluginKind::sensor,
                                             "0", "", nullptr, nullptr, nullptr, nullptr, nullptr};
    return &m;
}
}  // namespace
BOOST_DLL_ALIAS(manifest, rollsense_plugin_manifest)
