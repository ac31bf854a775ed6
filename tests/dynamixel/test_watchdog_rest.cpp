// Issue 22: the Bus Watchdog around long work on the script thread. A
// stock-like script on etroll-virtual (the dynamixel plugin on in-process
// emulated servos) records, rests (etroll.rest: parked, watchdog off),
// analyses, then rolls again as live identification does. The watchdog is
// read back over the bus (address 98, device:call('watchdog')) while resting
// and during the second roll: off, then re-armed by the first control period
// after the analysis. The run succeeds: a healthy run never trips it.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "runtime/session/session.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::testing::read_file;
namespace fs = std::filesystem;

TEST_CASE("after rs.analyse the next roll has every servo's Bus Watchdog armed again", "[fault][watchdog]") {
    const testing::TempDir tmp("rollsense-watchdog-rest");
    const fs::path& dir = tmp.path();
    std::ofstream(dir / "script.lua") << R"(
local rs = require "rollsense"
local etroll = require "etroll"
rs.on_cleanup(etroll.park)
local hand = rs.device("hand")
local function watchdogs(when, expect)
  for joint, ms in pairs(hand:call("watchdog")) do
    print(string.format("%s: %s Bus Watchdog %d ms", when, joint, ms))
    assert(ms == expect, when .. ": " .. joint .. "'s Bus Watchdog reads " .. ms .. " ms, expected " .. expect)
  end
end
watchdogs("recording", 500)
-- Two cylinders: the emulated hand rolls them clean at every speed, and the
-- analysis needs two classes among the clean trials.
for _, object in ipairs{ "C1", "C3" } do
  for repetition = 1, 3 do etroll.run_trial{ object = object, speed = 20, repetition = repetition } end
end
etroll.rest()
watchdogs("resting", 0)
local result = rs.analyse{ folds = 3 }
assert(result.trials == 6, "analysed " .. tostring(result.trials) .. " trials")
-- Live identification after the analysis: roll again, reading the watchdog mid-roll.
rs.trial{ object = "C1", speed = 20, repetition = 4, id = "identify-1" }
etroll.open()
etroll.clamp()
local sensing = rs.joint("sensing_finger")
local read_mid_roll = false
rs.spawn(function()
  rs.wait_until(function() return sensing:moving() and sensing:position() > 0 end, 20000)
  watchdogs("second roll", 500)
  read_mid_roll = true
end)
etroll.roll(20)
etroll.return_to_start()
etroll.release()
rs.end_trial()
assert(read_mid_roll, "the watchdog was not read during the second roll")
)";
    runtime::SessionOptions o;
    o.script = dir / "script.lua";
    o.profile = "etroll-virtual";
    o.share_dir = ROLLSENSE_SHARE_DIR;
    o.out_dir = dir / "out";
    o.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    runtime::Session session(o);
    const auto summary = session.run();
    INFO(summary.status.message());
    REQUIRE(summary.status.ok());
    CHECK(summary.trials_saved == 6);
    CHECK_THAT(read_file(dir / "out" / "run-info.csv"), Catch::Contains("status,ok"));
}
