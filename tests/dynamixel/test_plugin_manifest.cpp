// The built plugin module loads and describes itself as the kernel expects.
#include <catch2/catch.hpp>

#include <boost/dll/import.hpp>

#include "rollsense/plugin.hpp"

TEST_CASE("librollsense_dynamixel.so exports a matching actuator manifest") {
    const std::filesystem::path path = std::filesystem::path(ROLLSENSE_PLUGIN_DIR) / "librollsense_dynamixel.so";
    REQUIRE(std::filesystem::exists(path));
    auto manifest_fn = boost::dll::import_alias<rollsense::PluginManifestFn>(
        path, rollsense::kPluginManifestSymbol, boost::dll::load_mode::rtld_now);
    const rollsense::PluginManifest* m = manifest_fn();
    REQUIRE(m);
    CHECK(m->magic == rollsense::kPluginMagic);
    CHECK(m->abi_version == rollsense::kPluginAbiVersion);
    CHECK(std::string(m->name) == "dynamixel");
    CHECK(m->kind == rollsense::PluginKind::actuator);
    REQUIRE(m->create_actuator);
    const auto schema = m->schema();
    CHECK(schema.size() >= 10);
    rollsense::Actuator* a = m->create_actuator();
    REQUIRE(a);
    CHECK(a->joints().empty());  // nothing before configure
    m->destroy(a);
}
