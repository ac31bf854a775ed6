// A sensor plugin's faults the kernel catches itself (independent review items
// 4 and 5): a NaN in a frame the plugin calls valid, and channel names that
// would give the trial files one column twice.
#include <catch2/catch.hpp>

#include <cmath>

#include "kernel_fixture.hpp"
#include "runtime/profile/profile.hpp"
#include "runtime/robot/robot.hpp"

using namespace rollsense;
using namespace rollsense::runtime;

namespace {
// The test hand with `sensors` (Lua table entries) in place of its bump sensor.
Result<std::unique_ptr<Robot>> robot_with(const kt::TempDir& dir, const std::string& sensors) {
    std::string text = kt::kTestProfile;
    const std::string bump = "tactile = { plugin = \"example_bump\", params = { joint = \"finger\" } },";
    text.replace(text.find(bump), bump.size(), sensors);
    kt::write_file(dir / "profiles/p.lua", text);
    auto p = load_profile((dir / "profiles/p.lua").string(), dir.path(), {});
    if (!p) return p.error();
    PluginRegistry reg({ROLLSENSE_PLUGIN_DIR, ROLLSENSE_TEST_PLUGIN_DIR});
    return Robot::create(*p, reg, ROLLSENSE_SHARE_DIR);
}
// One sample of an activated robot, which is then shut down.
TrialData first_sample(Robot& robot) {
    REQUIRE(robot.activate(0.0).ok());
    TrialData data;
    REQUIRE(robot.sample(0.0, data).ok());
    robot.shutdown(0.0);
    return data;
}
}  // namespace

TEST_CASE("a NaN in a frame the plugin reports valid makes the sample invalid", "[robot][review]") {
    kt::TempDir dir;
    auto robot = robot_with(dir, "tactile = { plugin = \"test_faulty_sensor\", params = { nan_channel = 1 } },");
    REQUIRE(robot.ok());
    const TrialData data = first_sample(**robot);
    REQUIRE(data.valid.size() == 1);
    CHECK(data.valid[0] == 0);  // was 1: "every channel read fine" with a NaN in channel b
    CHECK(std::isnan(data.channels[1][0]));
    CHECK(data.channels[0][0] == 1.0);  // the value is kept as read; the row says it is not a reading

    kt::TempDir clean_dir;
    auto clean = robot_with(clean_dir, "tactile = { plugin = \"test_faulty_sensor\" },");
    REQUIRE(clean.ok());
    CHECK(first_sample(**clean).valid == std::vector<std::uint8_t>{1});
}

TEST_CASE("channel names that give one column twice are refused at configure time, naming device and plugin",
          "[robot][review]") {
    kt::TempDir dir;
    auto same = robot_with(dir, "tactile = { plugin = \"test_faulty_sensor\", params = { names = \"ch,ch,ch\" } },");
    REQUIRE_FALSE(same.ok());
    CHECK(same.error().code == ErrorCode::plugin_error);  // exit 3, as any plugin's error
    CHECK_THAT(same.error().message, Catch::Contains("p.lua:13: devices.tactile (plugin 'test_faulty_sensor')") &&
                                         Catch::Contains("the channel column 'ch' is taken") &&
                                         Catch::Contains("channel names must be unique"));
    // Across devices, through the <device>_<channel> prefix: a + b_c and a_b + c are both a_b_c.
    auto prefixed = robot_with(dir, "a = { plugin = \"test_faulty_sensor\", params = { names = \"b_c\" } },\n"
                                    "a_b = { plugin = \"test_faulty_sensor\", params = { names = \"c\" } },");
    REQUIRE_FALSE(prefixed.ok());
    CHECK_THAT(prefixed.error().message, Catch::Contains("the channel column 'a_b_c' is taken"));
    // The trial file's own columns are not channel names either.
    auto reserved = robot_with(dir, "tactile = { plugin = \"test_faulty_sensor\", params = { names = \"x,valid\" } },");
    REQUIRE_FALSE(reserved.ok());
    CHECK_THAT(reserved.error().message, Catch::Contains("the channel column 'valid' is taken"));
    // Distinct names are fine.
    CHECK(robot_with(dir, "tactile = { plugin = \"test_faulty_sensor\", params = { names = \"x,y\" } },").ok());
}

TEST_CASE("a channel name that would not stay one CSV column, or that a recorded joint's column takes, is refused",
          "[robot][review]") {
    kt::TempDir dir;
    // Each of these recorded a dataset whose dataset-info.csv rollsense then refused, or a header with an empty
    // column: an empty name, a space (dataset-info.csv lists channels space-separated), a quote.
    for (const char* names : {"x,,y", "x,p 2,y", "x,p\\\"3,y"}) {
        auto r = robot_with(dir, std::string("tactile = { plugin = \"test_faulty_sensor\", params = { names = \"") +
                                     names + "\" } },");
        INFO(names);
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().code == ErrorCode::plugin_error);
        CHECK_THAT(r.error().message, Catch::Contains("devices.tactile (plugin 'test_faulty_sensor')") &&
                                          Catch::Contains("free of spaces, commas and quotes"));
    }
    // The test hand records joint 'finger': a channel of that name gave the header time,finger,b,c,finger,valid.
    auto joint = robot_with(dir, "tactile = { plugin = \"test_faulty_sensor\", params = { names = \"finger,b\" } },");
    REQUIRE_FALSE(joint.ok());
    CHECK(joint.error().code == ErrorCode::invalid_argument);
    CHECK_THAT(joint.error().message, Catch::Contains("p.lua:19: record_joints.1 is 'finger', which is no usable column") &&
                                          Catch::Contains("taken by a channel"));
}

// Review (plugin author's journey): a sensor whose channels() threw gave
// "unexpected error: boom" with no device, plugin or profile.
TEST_CASE("a sensor whose channels() throws is a plugin error naming the device and the plugin", "[robot][review]") {
    kt::TempDir dir;
    auto robot = robot_with(dir, "tactile = { plugin = \"test_thrower\", params = { throw_in = \"channels\" } },");
    REQUIRE_FALSE(robot.ok());
    CHECK(robot.error().code == ErrorCode::plugin_error);
    CHECK_THAT(robot.error().message, Catch::Contains("device 'tactile' (plugin 'test_thrower')") &&
                                          Catch::Contains("threw an exception in channels: boom in channels"));
}
