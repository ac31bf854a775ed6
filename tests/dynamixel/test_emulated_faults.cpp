// Issue 22: every kind of injected servo fault, end to end through a Session
// on etroll-virtual (the in-process emulator, virtual clock: fast and
// deterministic). The run ends with a typed error naming the servo, the
// dataset holds only complete trials, and run-info.csv says how the run
// ended. (That the answering servos end in the safe state is read back over
// the bus in test_fault_safe_state.cpp, where the test owns the bus.)
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include <tuple>

#include "runtime/session/session.hpp"
#include "log_capture.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::testing::read_file;
namespace fs = std::filesystem;

namespace {

// A Session on etroll-virtual (or a profile in `dir` that includes it), as `rollsense run` starts one.
runtime::RunSummary run_session(const fs::path& dir, const fs::path& script, const std::string& profile,
                                std::initializer_list<const char*> settings) {
    runtime::SessionOptions o;
    o.script = script;
    o.profile = profile;
    for (const char* kv : settings) REQUIRE(o.settings.add(kv).ok());
    o.share_dir = ROLLSENSE_SHARE_DIR;
    o.out_dir = dir / "out";
    o.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    runtime::Session session(o);
    return session.run();
}

runtime::RunSummary run_with_fault(const fs::path& dir, const std::string& spec) {
    std::ofstream(dir / "faulty.lua") << "local p = include('etroll-virtual')\n"
                                         "p.devices.hand.params.inject = { '" << spec << "' }\n"
                                         "return p\n";
    return run_session(dir, fs::path(ROLLSENSE_SOURCE_DIR) / "scripts/paper_experiment.lua",
                       (dir / "faulty.lua").string(), {"runs=3", "objects=C1", "speeds=20", "analyse=false"});
}

}  // namespace

TEST_CASE("each injected servo fault ends the run with a typed error, complete trials only, and run-info",
          "[fault]") {
    for (auto [spec, code] : {std::pair{"1:silent:25", ErrorCode::timeout},
                              std::pair{"1:hardware-error:25", ErrorCode::hardware_fault},
                              std::pair{"2:corrupt:25", ErrorCode::protocol_error},
                              std::pair{"1:slow:25", ErrorCode::timeout}}) {
        INFO(spec);
        const testing::TempDir tmp("rollsense-emulated-fault");
        const auto summary = run_with_fault(tmp.path(), spec);
        INFO(summary.status.message());
        REQUIRE_FALSE(summary.status.ok());
        CHECK(summary.status.code() == code);
        const std::string servo = std::string("servo ") + spec[0];
        CHECK_THAT(summary.status.message(), Catch::Contains("device 'hand'") && Catch::Contains(servo));
        CHECK(summary.trials_saved < 3);  // the fault came before the end
        // Only complete trials: every file in trials/ is in the manifest, and
        // the manifest lists exactly the trials saved.
        const fs::path out = tmp.path() / "out";
        const std::string manifest = read_file(out / "manifest.csv");
        std::size_t files = 0;
        if (fs::exists(out / "trials"))
            for (const auto& f : fs::directory_iterator(out / "trials")) {
                ++files;
                CHECK_THAT(manifest, Catch::Contains(f.path().stem().string()));
            }
        CHECK(files == summary.trials_saved);
        const std::string info = read_file(out / "run-info.csv");
        CHECK_THAT(info, Catch::Contains("status"));
        CHECK_THAT(info, Catch::Contains(servo));
    }
}

// Review finding 9: a silent servo was printed three times: when the device
// entered its error state, again by the script's cleanup (whose park() the
// device refused), and as the run's error. It is the run's error only now;
// the cleanup's refusal names the fault's kind, not its text. A hardware error
// was printed twice: by the plugin when it read the alert, then as the run's error.
TEST_CASE("a servo fault is reported once, as the run's error", "[fault]") {
    for (auto [spec, code, text, kind] :
         {std::tuple{"1:silent:25", ErrorCode::timeout, "did not answer", "(after its fault: timeout)"},
          std::tuple{"1:hardware-error:25", ErrorCode::hardware_fault, "overload", "(after its fault: hardware fault)"}}) {
        INFO(spec);
        const testing::TempDir tmp("rollsense-emulated-fault-once");
        const testing::LogCapture log(LogLevel::info);
        const auto summary = run_with_fault(tmp.path(), spec);
        INFO(log.all());
        REQUIRE(summary.status.code() == code);
        CHECK_THAT(summary.status.message(), Catch::Contains(text));
        CHECK(log.count(text) == 0);
        CHECK(log.count("cleanup stopped") == 1);
        CHECK(log.count(std::string("needs the active state, it is error ") + kind) == 1);
        for (const auto& line : log.lines()) CHECK(line.rfind("error ", 0) != 0);  // nothing else at error level
    }
}

// The independent hardware review's repros on etroll-virtual: a finger pushing
// with nothing in its way past its limit (item 1), and a control period longer
// than the servos' Bus Watchdog (item 2).
// The finger went on to 824 deg (the servo's position limits act in position mode only).
TEST_CASE("etroll-virtual: the pushing finger in current mode with no object stops at its limit", "[limits][review]") {
    const testing::TempDir tmp("rollsense-push-free");
    std::ofstream(tmp.path() / "script.lua") << R"(
local rs = require "rollsense"
local p = rs.joint("pushing_finger")
rs.on_cleanup(function()
  rs.wait(1000)
  rs.write_output("held.txt", string.format("%.2f %s %s", p:position(), p:state().mode, tostring(p:state().torque)))
end)
p:push(200)
rs.wait(3000)
rs.write_output("not_stopped.txt", string.format("%.1f", p:position()))
)";
    const auto summary = run_session(tmp.path(), tmp.path() / "script.lua", "etroll-virtual", {"emulated_object=0"});
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
    std::ofstream(tmp.path() / "script.lua") << R"(
local rs = require "rollsense"
rs.wait(2000)
rs.joint("sensing_finger"):move(30, { timeout_ms = 8000 })
)";
    const auto summary = run_session(tmp.path(), tmp.path() / "script.lua", (tmp.path() / "slow.lua").string(), {});
    REQUIRE_FALSE(summary.status.ok());
    CHECK(summary.status.code() == ErrorCode::hardware_fault);
    CHECK_THAT(summary.status.message(), Catch::Contains("(servo 1): its Bus Watchdog (address 98) tripped: no "
                                                         "instruction reached it for 500 ms"));
}
