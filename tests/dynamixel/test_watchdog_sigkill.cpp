// Issue 22: what the process cannot catch, the servos catch themselves. A
// `rollsense run` on the emulated E-TRoll bus (a pty served by this test, real
// time, wire timing at the line rate) is SIGKILLed mid-roll, with the pushing
// finger clamping the object in current mode. Within the Bus Watchdog time
// (500 ms by default, the longest setting is 2.54 s) a fresh client reads
// over the bus: every servo that had torque on reports the watchdog error,
// and the pushing finger no longer pushes. Real time: about 10 s.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "etroll_bus.hpp"
#include "rollsense/hal/dynamixel/bus.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::hal::dxl;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {
constexpr double kSafeCurrentMa = 20.0;  // a stopped finger draws next to nothing
}

TEST_CASE("a SIGKILLed run leaves every torqued servo stopped by its Bus Watchdog", "[safety][watchdog]") {
    auto emu = etroll_bus::start();

    const testing::TempDir tmp("rollsense-sigkill");
    std::ofstream(tmp.path() / "script.lua") << R"(
local rs = require "rollsense"
local etroll = require "etroll"
rs.trial{ object = "C2", speed = 5, repetition = 1 }
etroll.open()
etroll.clamp()
etroll.roll(5)   -- slow: the kill comes well before its end
)";
    const std::string exe = std::string(ROLLSENSE_BIN_DIR) + "/rollsense";
    const std::string script = (tmp.path() / "script.lua").string();
    const std::string out = (tmp.path() / "out").string();
    const std::string device = "dxl_device=" + emu->device();
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ::execl(exe.c_str(), exe.c_str(), "run", script.c_str(), "--profile", "etroll-emulated", "--set",
                device.c_str(), "--out", out.c_str(), "-q", static_cast<char*>(nullptr));
        ::_exit(127);
    }

    // Mid-roll: the pushing finger clamps (> 100 mA) and the sensing finger moves.
    bool rolling = false;
    const auto give_up = Clock::now() + std::chrono::seconds(60);
    while (!rolling && Clock::now() < give_up) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        rolling = emu->with_bus([](BusEmulator& b) {
            return std::abs(b.servo(2)->current_ma()) > 100 && std::abs(b.servo(1)->velocity_ticks_s()) > 1;
        });
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid) FAIL("rollsense ended before the roll (exit " << status << ")");
    }
    if (!rolling) ::kill(pid, SIGKILL);
    REQUIRE(rolling);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const auto torqued = emu->with_bus([](BusEmulator& b) {
        std::vector<std::uint8_t> ids;
        for (auto id : b.ids())
            if (b.servo(id)->torque_enabled()) ids.push_back(id);
        return ids;
    });
    REQUIRE(::kill(pid, SIGKILL) == 0);
    const auto killed = Clock::now();
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    REQUIRE(WIFSIGNALED(status));
    REQUIRE(torqued.size() == 4);  // the whole hand was holding or pushing

    // The default watchdog is 500 ms; read back after it, well within 2.54 s.
    std::this_thread::sleep_until(killed + std::chrono::milliseconds(800));
    auto port = hal::SerialPort::open(emu->device(), 1'000'000);
    REQUIRE(port.ok());
    Bus client(std::move(port).value(), BusOptions{std::chrono::milliseconds(100), 3});
    for (auto id : torqued) {
        INFO("servo " << int(id));
        auto watchdog = client.read_value(id, addr::bus_watchdog, 1);
        REQUIRE(watchdog.ok());
        CHECK(*watchdog == -1);
    }
    auto current = client.read_value(2, addr::present_current, 2);
    REQUIRE(current.ok());
    const auto* model = emu->with_bus([](BusEmulator& b) { return &b.servo(2)->model(); });
    CHECK(std::abs(current_units_to_ma(*model, *current)) <= kSafeCurrentMa);
    CHECK(Clock::now() - killed < std::chrono::milliseconds(2540));
}
