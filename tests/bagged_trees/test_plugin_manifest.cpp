// The built plugin module exports a manifest the kernel's loader can use.
#include <catch2/catch.hpp>

#include <boost/dll/shared_library.hpp>

#include "rollsense/plugin.hpp"
#include "toy_data.hpp"

TEST_CASE("the bagged_trees module exports a classifier manifest", "[bagged_trees][plugin]") {
    const auto path = std::filesystem::path(ROLLSENSE_PLUGIN_DIR) / "librollsense_bagged_trees.so";
    boost::dll::shared_library lib(path);
    auto manifest_fn = lib.get_alias<rollsense::PluginManifestFn>(rollsense::kPluginManifestSymbol);
    const rollsense::PluginManifest* m = manifest_fn();
    REQUIRE(m->magic == rollsense::kPluginMagic);
    REQUIRE(m->abi_version == rollsense::kPluginAbiVersion);
    CHECK(std::string(m->name) == "bagged_trees");
    CHECK(m->kind == rollsense::PluginKind::classifier);
    REQUIRE(m->create_classifier != nullptr);
    CHECK(m->create_sensor == nullptr);
    auto schema = m->schema();
    CHECK(std::any_of(schema.begin(), schema.end(), [](const auto& s) { return s.name == "learners"; }));

    rollsense::Classifier* c = m->create_classifier();
    REQUIRE(c->train(toy::separable(60, 1)).ok());
    auto p = c->predict(std::vector<double>{0.9, 0.5, 0.5});
    REQUIRE(p.ok());
    CHECK(p->class_name == "K2");
    m->destroy(c);
}
