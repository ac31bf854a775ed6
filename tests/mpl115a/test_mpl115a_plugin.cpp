// The built plugin library, loaded through its manifest like the kernel does,
// passes the sensor conformance suite on a modelled strip; so does the class.
#include <catch2/catch.hpp>

#include <boost/dll/shared_library.hpp>

#include "rollsense/testing/conformance.hpp"
#include "mpl115a_test_rig.hpp"
#include "rollsense/plugin.hpp"

using namespace rollsense;
using namespace mpl115a_test;

namespace {

const PluginManifest& manifest() {
    // Loaded once and kept for the whole run: instances must not outlive their code.
    static boost::dll::shared_library lib(std::string(ROLLSENSE_PLUGIN_DIR) + "/librollsense_mpl115a.so",
                                          boost::dll::load_mode::rtld_now);
    static const PluginManifest* m = lib.get_alias<PluginManifestFn>(kPluginManifestSymbol)();
    return *m;
}

ParamSet plugin_params(const std::string& bus, ValueMap extra = {}) {
    extra["bus"] = bus;
    auto r = validate_params(manifest().schema(), extra, "test profile: devices.tactile");
    INFO((r.ok() ? std::string() : r.error().message));
    REQUIRE(r.ok());
    return r.value();
}

}  // namespace

TEST_CASE("the manifest describes a sensor plugin named mpl115a", "[mpl115a][plugin]") {
    const auto& m = manifest();
    CHECK(m.magic == kPluginMagic);
    CHECK(m.abi_version == kPluginAbiVersion);
    CHECK(std::string(m.name) == "mpl115a");
    CHECK(m.kind == PluginKind::sensor);
    REQUIRE(m.create_sensor);
    std::vector<std::string> names;
    for (const auto& p : m.schema()) names.push_back(p.name);
    for (const char* expected : {"bus", "strip", "sensors", "scale", "conversion_time_ms"})
        CHECK(std::find(names.begin(), names.end(), expected) != names.end());
}

TEST_CASE("the loaded plugin passes the sensor conformance suite", "[mpl115a][plugin][conformance]") {
    Rig rig("conformance-plugin");
    testing::SensorConformance c;
    c.make = [] { return std::unique_ptr<Sensor>(manifest().create_sensor()); };
    c.params = plugin_params(rig.spec, {{"raw_channels", true}});
    testing::check_sensor_conformance(c);
}

TEST_CASE("the class passes the sensor conformance suite with three of twelve sensors", "[mpl115a][conformance]") {
    // The paper's rig: two strips back to back, three adjacent sensors active.
    Rig rig("conformance-class");
    rig.bus->attach(std::make_shared<rollsense::hal::TakkStripModel>(rollsense::hal::TakkStripModelConfig{.strip = 1}));
    testing::SensorConformance c;
    c.make = [] { return std::make_unique<plugins::Mpl115aSensor>(); };
    c.params = params(rig.spec, {{"select_addresses", std::vector<std::int64_t>{4, 5, 8}}});
    testing::check_sensor_conformance(c);
}

TEST_CASE("simulate = true attaches a modelled strip to an empty fake bus", "[mpl115a][plugin]") {
    auto bus = rollsense::hal::FakeI2cBus::get("simulated");
    bus->reset();
    std::unique_ptr<Sensor> s(manifest().create_sensor());
    REQUIRE(s->on_configure(plugin_params("fake:simulated", {{"simulate", true}}), {}).ok());
    REQUIRE(s->start_recording({}).ok());
    auto f = read_frame(*s);
    CHECK(f.valid);
    for (double v : f.values) CHECK(std::abs(v) < 0.05);  // ambient, a count or two of noise

    // On a real bus spec, simulate cannot help: the error stays the real one.
    std::unique_ptr<Sensor> real(manifest().create_sensor());
    auto st = real->on_configure(plugin_params("/dev/i2c-247", {{"simulate", true}}), {});
    CHECK(st.code() == ErrorCode::not_found);
}
