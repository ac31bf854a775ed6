// Helpers for kernel tests: a temporary folder, and running a Lua script on a
// small mock hand through a real Session (plugins loaded from the build).
#pragma once

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "rollsense/hal/gpio.hpp"
#include "runtime/session/session.hpp"
#include "temp_dir.hpp"

namespace kt {

namespace fs = std::filesystem;

using rollsense::testing::read_file;
using rollsense::testing::TempDir;
using rollsense::testing::write_file;

// Two servo joints and a three-cell bump sensor on the virtual clock.
inline const char* kTestProfile = R"(
return {
  description = "test hand",
  clock = "virtual",
  sample_rate_hz = 31.1,
  control_rate_hz = 100,
  devices = {
    hand = { plugin = "mock_actuator", params = {
      joints = { "finger", "pusher" }, units = { "deg", "deg" },
      min = { -90, -90 }, max = { 90, 90 }, initial = { 0, 0 },
      max_velocity = { 100, 100 }, max_current = { 500, 500 }, contact = { 0/0, 20 },
      free_speed_per_ma = 0.2, extended = {} } },
    tactile = { plugin = "example_bump", params = { joint = "finger" } },
  },
  joints = {
    finger = { min = -50, max = 50, max_velocity = 60, max_current = 300 },
    pusher = { min = -60, max = 60, max_velocity = 60, max_current = 300, safe = "torque_off" },
  },
  record_joints = { "finger" },
}
)";

struct ScriptRun {
    rollsense::runtime::RunSummary summary;
    fs::path out;
};

inline rollsense::runtime::SessionOptions options_for(const TempDir& dir, const std::string& script,
                                                      const std::string& profile = kTestProfile) {
    write_file(dir / "script.lua", script);
    write_file(dir / "profiles/test.lua", profile);
    rollsense::runtime::SessionOptions o;
    o.script = dir / "script.lua";
    o.profile = (dir / "profiles/test.lua").string();
    o.share_dir = ROLLSENSE_SHARE_DIR;
    o.out_dir = dir / "out";
    o.plugin_path = {ROLLSENSE_PLUGIN_DIR, ROLLSENSE_TEST_PLUGIN_DIR};
    o.sandbox.max_slice_ms = 1000;
    o.digital_lines = rollsense::hal::gpio_digital_lines();  // e-stop and trigger on fake chips
    return o;
}

inline ScriptRun run_script(const TempDir& dir, const std::string& script, const std::string& profile = kTestProfile) {
    auto o = options_for(dir, script, profile);
    rollsense::runtime::Session session(o);
    return {session.run(), o.out_dir};
}

}  // namespace kt
