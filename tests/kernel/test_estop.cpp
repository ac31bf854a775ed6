// Emergency stop and trigger output, end to end through the fake GPIO chip.
#include <catch2/catch.hpp>

#include <thread>

#include "kernel_fixture.hpp"
#include "rollsense/hal/gpio.hpp"

using namespace rollsense;

namespace {
std::string profile_with_safety(const std::string& chip) {
    std::string p = kt::kTestProfile;
    const std::string anchor = "record_joints = { \"finger\" },";
    p.replace(p.find(anchor), anchor.size(),
              anchor + "\n  safety = { estop = { chip = \"fake:" + chip + "\", line = 3 },"
                       " trigger = { chip = \"fake:" + chip + "\", line = 5, pulse_ms = 4 } },");
    return p;
}
}  // namespace

TEST_CASE("asserting the emergency stop mid-roll cancels the script and stops every joint", "[estop]") {
    kt::TempDir dir;
    auto chip = hal::FakeGpioChip::get("estop-roll");
    chip->set_input_level(3, false);
    auto o = kt::options_for(dir, R"(local rs = require 'rollsense'
local f = rs.joint("finger")
rs.on_cleanup(function()
  rs.wait(500)
  local moved, err = pcall(f.move, f, 0)
  rs.write_output("cleanup.txt", string.format("%s %s|%s", tostring(f:moving()), tostring(moved), tostring(err)))
end)
while true do
  f:move(40, { velocity = 20 }); f:move(-40, { velocity = 20 })
end
)", profile_with_safety("estop-roll"));
    rollsense::runtime::Session session(o);
    std::thread press([chip] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        chip->set_input_level(3, true);
    });
    auto s = session.run();
    press.join();
    REQUIRE_FALSE(s.status.ok());
    CHECK(s.status.code() == ErrorCode::cancelled);
    CHECK_THAT(s.status.message(), Catch::Contains("emergency stop asserted"));
    auto out = kt::read_file(o.out_dir / "cleanup.txt");
    CHECK_THAT(out, Catch::StartsWith("false false|"));  // stopped, and new motion refused
    CHECK_THAT(out, Catch::Contains("emergency stop asserted; commands are refused"));
    chip->set_input_level(3, false);
}

TEST_CASE("a run does not start while the emergency stop is asserted", "[estop]") {
    kt::TempDir dir;
    auto chip = hal::FakeGpioChip::get("estop-held");
    chip->set_input_level(3, true);
    auto r = kt::run_script(dir, "local rs = require 'rollsense'\nrs.wait(10)\n", profile_with_safety("estop-held"));
    REQUIRE_FALSE(r.summary.status.ok());
    CHECK_THAT(r.summary.status.message(), Catch::Contains("is asserted; release it before starting"));
}

TEST_CASE("a missing GPIO chip is a configuration error naming the profile entry", "[estop]") {
    kt::TempDir dir;
    std::string p = kt::kTestProfile;
    const std::string anchor = "record_joints = { \"finger\" },";
    p.replace(p.find(anchor), anchor.size(), anchor + " safety = { estop = { chip = \"gpiochip77\", line = 1 } },");
    auto r = kt::run_script(dir, "local rs = require 'rollsense'\n", p);
    REQUIRE_FALSE(r.summary.status.ok());
    CHECK_THAT(r.summary.status.message(), Catch::Contains("safety.estop"));
    CHECK_THAT(r.summary.status.message(), Catch::Contains("gpiochip77"));
}

TEST_CASE("the trigger output pulses at the start of every recording", "[trigger]") {
    kt::TempDir dir;
    auto chip = hal::FakeGpioChip::get("trigger-pulses");
    chip->set_input_level(3, false);
    chip->clear_output_history();
    auto r = kt::run_script(dir, R"(local rs = require 'rollsense'
for i = 1, 2 do
  rs.trial{ id = "t" .. i }
  rs.record_start(); rs.wait(100); rs.record_stop(); rs.end_trial()
end
)", profile_with_safety("trigger-pulses"));
    REQUIRE(r.summary.status.ok());
    std::vector<bool> levels;
    for (auto [line, level] : chip->output_history())
        if (line == 5) levels.push_back(level);
    CHECK(levels == std::vector<bool>{false, true, false, true, false});
}
