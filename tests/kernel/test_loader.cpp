// Plugin loading through Boost.DLL: real plugins load; every failure mode is
// reported with its reason; instances keep their library loaded.
#include <catch2/catch.hpp>

#include <map>

#include "kernel_fixture.hpp"
#include "log_capture.hpp"
#include "runtime/plugin/plugin_registry.hpp"

using namespace rollsense;
using namespace rollsense::runtime;
namespace fs = std::filesystem;

namespace {
fs::path test_plugin(const std::string& name) { return fs::path(ROLLSENSE_TEST_PLUGIN_DIR) / ("lib" + name + ".so"); }
}  // namespace

TEST_CASE("a real plugin library loads and creates a working instance", "[loader]") {
    PluginRegistry reg({ROLLSENSE_PLUGIN_DIR});
    auto sensor = reg.create_sensor("example_bump", "tactile");
    REQUIRE(sensor.ok());
    auto& h = **sensor;
    CHECK(h.plugin_name() == "example_bump");
    CHECK(h.instance() == "tactile");
    auto lib = reg.find("example_bump", PluginKind::sensor);
    REQUIRE(lib.ok());
    auto schema = PluginRegistry::schema_of(**lib);
    REQUIRE(schema.ok());
    auto params = validate_params(*schema, {}, "test");
    REQUIRE(params.ok());
    REQUIRE(h.configure(*params, {}).ok());
    CHECK(h.plugin().channels().size() == 3);
}

TEST_CASE("an instance keeps its library loaded after the registry is gone", "[loader]") {
    std::unique_ptr<ActuatorHandle> handle;
    {
        PluginRegistry reg({ROLLSENSE_PLUGIN_DIR});
        auto a = reg.create_actuator("mock_actuator", "hand");
        REQUIRE(a.ok());
        handle = std::move(*a);
    }
    // Calling into the plugin's code after its registry died must work.
    auto joints = handle->plugin().joints();  // unconfigured: empty, but the vtable is live
    CHECK(joints.empty());
    handle.reset();  // destroyed through the plugin's destroy() while still mapped
}

TEST_CASE("a library without the manifest symbol is reported as not a plugin", "[loader]") {
    auto c = PluginRegistry::load_file(test_plugin("rollsense_test_no_manifest"));
    CHECK_FALSE(c.library);
    CHECK_THAT(c.failure, Catch::Contains("missing symbol 'rollsense_plugin_manifest'"));
}

TEST_CASE("a plugin whose name is not a-z, 0-9 and _ is refused, naming the name", "[loader]") {
    auto c = PluginRegistry::load_file(test_plugin("rollsense_test_bad_name"));
    CHECK_FALSE(c.library);
    CHECK_THAT(c.failure, Catch::Contains("its name 'dash-name' is not made of a-z, 0-9 and _") &&
                              Catch::Contains("ROLLSENSE_PLUGIN"));
}

TEST_CASE("a plugin built for another ABI is reported as an ABI mismatch", "[loader]") {
    auto c = PluginRegistry::load_file(test_plugin("rollsense_test_bad_abi"));
    CHECK_FALSE(c.library);
    CHECK_THAT(c.failure, Catch::Contains("ABI mismatch"));
    CHECK_THAT(c.failure, Catch::Contains(std::to_string(kPluginAbiVersion + 41)));
}

// Review (plugin author's journey): a constructor that threw 42 ended the
// process; a symbol no library defines killed a run at its first call
// (lazy binding); a plugin built with -D_GLIBCXX_DEBUG loaded and crashed.
TEST_CASE("a plugin that throws a non-exception or lacks a symbol or uses debug containers is refused by name", "[loader]") {
    PluginRegistry reg({ROLLSENSE_TEST_PLUGIN_DIR});
    auto thrown = reg.create_sensor("test_ctor_thrower", "tactile");
    REQUIRE_FALSE(thrown.ok());
    CHECK(thrown.error().code == ErrorCode::plugin_error);
    CHECK(thrown.error().message == "plugin 'test_ctor_thrower': constructor threw a non-std::exception");
    // Review (plugins): through a profile, the refusal names the device and the profile's line, as every hook's does.
    kt::TempDir dir;
    std::string profile = kt::kTestProfile;
    profile.replace(profile.find("plugin = \"example_bump\", params = { joint = \"finger\" }"),
                    std::string("plugin = \"example_bump\", params = { joint = \"finger\" }").size(), "plugin = \"test_ctor_thrower\"");
    const auto run = kt::run_script(dir, "print('never')\n", profile);
    REQUIRE_FALSE(run.summary.status.ok());
    CHECK_THAT(run.summary.status.message(),
               Catch::Contains("test.lua:") && Catch::Contains("devices.tactile") &&
                   Catch::Contains("plugin 'test_ctor_thrower': constructor threw a non-std::exception"));

    auto undefined = PluginRegistry::load_file(test_plugin("rollsense_test_undefined"));
    CHECK_FALSE(undefined.library);
    CHECK_THAT(undefined.failure, Catch::Contains("cannot be loaded") && Catch::Contains("rollsense_test_defined_nowhere"));
    auto asked = reg.find("test_undefined", PluginKind::sensor);
    REQUIRE_FALSE(asked.ok());  // and asked for by name, the refused file comes first
    CHECK_THAT(asked.error().message, Catch::StartsWith("no sensor plugin named 'test_undefined' loads: ") &&
                                          Catch::Contains("librollsense_test_undefined.so is not used: cannot be loaded"));

    auto debug = PluginRegistry::load_file(test_plugin("rollsense_test_debug_stdlib"));
    CHECK_FALSE(debug.library);
    CHECK_THAT(debug.failure, Catch::Contains("ABI mismatch") && Catch::Contains("-glibcxxdebug") &&
                                  Catch::Contains("without -D_GLIBCXX_DEBUG"));
}

TEST_CASE("a file that is not a shared library is reported with the loader's reason", "[loader]") {
    kt::TempDir dir;
    kt::write_file(dir / "librollsense_fake.so", "this is text, not ELF\n");
    auto c = PluginRegistry::load_file(dir / "librollsense_fake.so");
    CHECK_FALSE(c.library);
    CHECK_THAT(c.failure, Catch::Contains("cannot be loaded"));
    CHECK_THAT(c.failure, Catch::Contains("librollsense_fake.so"));
}

// Review finding 5: a truncated library crashed every command with SIGBUS
// (dlopen mapped pages past the file's end) before the check.
TEST_CASE("a truncated plugin library is reported with its size and what its headers need", "[loader]") {
    kt::TempDir dir;
    const fs::path whole = fs::path(ROLLSENSE_PLUGIN_DIR) / "librollsense_example_bump.so";
    const auto size = fs::file_size(whole);
    for (const std::uintmax_t cut : {size / 2, std::uintmax_t{5000}, size - 1}) {
        INFO(cut);
        const fs::path damaged = dir / ("librollsense_cut" + std::to_string(cut) + ".so");
        fs::copy_file(whole, damaged);
        fs::resize_file(damaged, cut);
        auto c = PluginRegistry::load_file(damaged);
        CHECK_FALSE(c.library);
        CHECK_THAT(c.failure, Catch::StartsWith("truncated: " + std::to_string(cut) + " bytes, its headers need ") &&
                                  Catch::Contains("rebuild"));
    }
    PluginRegistry reg({dir.path()});
    CHECK(reg.scan().size() == 3);  // listed, not crashed on
    fs::copy_file(whole, dir / "librollsense_whole.so");
    CHECK(PluginRegistry::load_file(dir / "librollsense_whole.so").library);  // an intact copy still loads
}

TEST_CASE("a missing plugin names every folder searched and every file found", "[loader]") {
    kt::TempDir dir;
    kt::write_file(dir / "libjunk.so", "junk");
    PluginRegistry reg({dir.path(), ROLLSENSE_TEST_PLUGIN_DIR, "/nonexistent/plugins"});
    auto r = reg.find("no_such_plugin", PluginKind::sensor);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::not_found);
    const auto& m = r.error().message;
    CHECK_THAT(m, Catch::Contains("no sensor plugin named 'no_such_plugin'"));
    CHECK_THAT(m, Catch::Contains(dir.path().string()));
    CHECK_THAT(m, Catch::Contains("/nonexistent/plugins (no such folder)"));
    CHECK_THAT(m, Catch::Contains("libjunk.so: cannot be loaded"));
    CHECK_THAT(m, Catch::Contains("ABI mismatch"));
    CHECK_THAT(m, Catch::Contains("missing symbol"));
}

TEST_CASE("asking for a plugin of the wrong kind says which kind it is", "[loader]") {
    PluginRegistry reg({ROLLSENSE_PLUGIN_DIR});
    auto r = reg.find("mock_actuator", PluginKind::sensor);
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error().message, Catch::Contains("is an actuator plugin, not a sensor"));
}

// User review (out-of-tree plugins): the copy a folder earlier in the search path overrides (a build's --plugin-path
// over the installed one) is the search order at work; two of one name in one folder are a mistake.
TEST_CASE("a second plugin with the same name is reported as shadowed, overridden when in a later folder", "[loader]") {
    kt::TempDir dir;
    const fs::path bump = fs::path(ROLLSENSE_PLUGIN_DIR) / "librollsense_example_bump.so";
    fs::create_directories(dir / "later");
    fs::copy_file(bump, dir / "later" / "librollsense_copy.so");
    fs::copy_file(bump, dir / "librollsense_a.so");
    fs::copy_file(bump, dir / "librollsense_b.so");
    PluginRegistry reg({dir.path(), dir / "later"});
    std::map<std::string, const PluginCandidate*> by_file;
    for (const auto& c : reg.scan()) by_file[c.path.filename().string()] = &c;
    REQUIRE(by_file.size() == 3);
    CHECK(by_file["librollsense_a.so"]->library);
    CHECK(by_file["librollsense_b.so"]->failure ==
          "shadowed: a plugin named 'example_bump' was already found at " + (dir / "librollsense_a.so").string() +
              ", in the same folder");
    CHECK_FALSE(by_file["librollsense_b.so"]->overridden);
    CHECK_THAT(by_file["librollsense_copy.so"]->failure, Catch::EndsWith(", earlier in the search path"));
    CHECK(by_file["librollsense_copy.so"]->overridden);

    // Used, the plugin says once which of the two in one folder runs (plugin review: a stale build ran silently);
    // the copy a later folder holds is the search order at work, not said.
    rollsense::testing::LogCapture log;
    REQUIRE(reg.find("example_bump", PluginKind::sensor).ok());
    REQUIRE(reg.find("example_bump", PluginKind::sensor).ok());
    INFO(log.all());
    REQUIRE(log.lines().size() == 1);
    CHECK_THAT(log.lines().front(), Catch::StartsWith("warning plugins: " + (dir / "librollsense_b.so").string() +
                                                      " is not used: shadowed: a plugin named 'example_bump'") &&
                                        Catch::Contains("Plugin 'example_bump' comes from " +
                                                        (dir / "librollsense_a.so").string() + " instead"));
}

// Review (s8 item 2): a damaged copy earlier in the search path (e.g. a rebuild cut short in a
// --plugin-path folder) was skipped in silence and the installed plugin of that name ran instead.
TEST_CASE("a damaged file that would shadow a plugin is named once when its namesake is used", "[loader]") {
    kt::TempDir dir;
    const fs::path whole = fs::path(ROLLSENSE_PLUGIN_DIR) / "librollsense_example_bump.so";
    const fs::path damaged = dir / whole.filename();
    fs::copy_file(whole, damaged);
    fs::resize_file(damaged, fs::file_size(whole) / 2);
    kt::write_file(dir / "librollsense_other.so", "junk, but no namesake of a plugin that is used\n");
    rollsense::testing::LogCapture log;
    PluginRegistry reg({dir.path(), ROLLSENSE_PLUGIN_DIR});
    REQUIRE(reg.scan().size() >= 3);
    CHECK(log.lines().empty());  // listing (`rollsense plugins`) shows the failure itself
    REQUIRE(reg.find("example_bump", PluginKind::sensor).ok());
    REQUIRE(reg.create_sensor("example_bump", "second").ok());
    INFO(log.all());
    REQUIRE(log.lines().size() == 1);  // once, however often the plugin is asked for
    const std::string line = log.lines().front();
    CHECK_THAT(line, Catch::StartsWith("warning plugins: " + damaged.string() + " is not used: truncated: "));
    CHECK_THAT(line, Catch::Contains("Plugin 'example_bump' comes from " + whole.string() + " instead"));
    CHECK_THAT(line, Catch::Contains("rollsense plugins"));
    // A damaged file later in the search path shadows nothing: no warning.
    rollsense::testing::LogCapture later;
    PluginRegistry reversed({ROLLSENSE_PLUGIN_DIR, dir.path()});
    REQUIRE(reversed.find("example_bump", PluginKind::sensor).ok());
    CHECK(later.lines().empty());
}
