// The independent hardware review's repros on etroll-virtual (the dynamixel
// plugin on in-process emulated servos, the run clock virtual: fast and exact):
// a finger pushing with nothing in its way past its limit (item 1), and a
// control period longer than the servos' Bus Watchdog (item 2).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "runtime/session/session.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::testing::read_file;
namespace fs = std::filesystem;

namespace {

runtime::RunSummary run(const fs::path& dir, const std::string& script, const std::string& profile,
                        const char* setting = nullptr) {
    std::ofstream(dir / "script.lua") << script;
    runtime::SessionOptions o;
    o.script = dir / "script.lua";
    o.profile = profile;
    if (setting) REQUIRE(o.settings.add(setting).ok());
    o.share_dir = ROLLSENSE_SHARE_DIR;
    o.out_dir = dir / "out";
    o.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    o.progress = false;
    runtime::Session session(o);
    return session.run();
}

}  // namespace

// It went on to 824 deg (the servo's position limits act in position mode only).
TEST_CASE("etroll-virtual: the pushing finger in current mode with no object stops at its limit", "[limits][review]") {
    const testing::TempDir tmp("rollsense-push-free");
    const auto summary = run(tmp.path(), R"(
local rs = require "rollsense"
local p = rs.joint("pushing_finger")
rs.on_cleanup(function()
  rs.wait(1000)
  rs.write_output("held.txt", string.format("%.2f %s %s", p:position(), p:state().mode, tostring(p:state().torque)))
end)
p:push(200)
rs.wait(3000)
rs.write_output("not_stopped.txt", string.format("%.1f", p:position()))
)", "etroll-virtual", "emulated_object=0");
    REQUIRE_FALSE(summary.status.ok());
    CHECK(summary.status.code() == ErrorCode::limit_violation);
    CHECK_THAT(summary.status.message(), Catch::Contains("joint 'pushing_finger' in current mode is at 60.") &&
                                             Catch::Contains("past its limit 60 (joint limits [-80, 60] of profile "
                                                             "'etroll-virtual'"));
    CHECK_FALSE(fs::exists(tmp.path() / "out" / "not_stopped.txt"));
    double at = 0;
    char mode[32] = {}, torque[8] = {};
    REQUIRE(std::sscanf(read_file(tmp.path() / "out" / "held.txt").c_str(), "%lf %31s %7s", &at, mode, torque) == 3);
    CHECK(at == Approx(60).margin(0.1));  // held at the limit, to a tick (0.088 deg)
    CHECK(std::string(mode) == "position");
    CHECK(std::string(torque) == "true");
}

// The trip was never noticed: the move timed out with no word about the watchdog.
TEST_CASE("etroll-virtual: control periods longer than the Bus Watchdog end the run naming it", "[fault][watchdog][review]") {
    const testing::TempDir tmp("rollsense-slow-control");
    std::ofstream(tmp.path() / "slow.lua") << "local p = include('etroll-virtual')\np.control_rate_hz = 1\nreturn p\n";
    const auto summary = run(tmp.path(), R"(
local rs = require "rollsense"
rs.wait(2000)
rs.joint("sensing_finger"):move(30, { timeout_ms = 8000 })
)", (tmp.path() / "slow.lua").string());
    REQUIRE_FALSE(summary.status.ok());
    CHECK(summary.status.code() == ErrorCode::hardware_fault);
    CHECK_THAT(summary.status.message(), Catch::Contains("(servo 1): its Bus Watchdog (address 98) tripped: no "
                                                         "instruction reached it for 500 ms"));
}
