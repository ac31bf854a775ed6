// Issue 22: the process never ends without having tried the safe state on
// every device, even when nothing ordinary can run: a Lua panic, std::terminate,
// and a std::bad_alloc escaping the kernel's own work. Each happens in a forked
// child running a Session on the emulated E-TRoll (the bus on a pty served by
// this test, real time) while the pushing finger clamps the object; the child
// must send the prepared last resort (every servo's torque off, packets made
// at activation, no heap, no Lua) and record how the run ended. The test reads
// every servo back over the bus afterwards. About 3 s per case.
//
// This binary replaces the global operator new so that a test can make the
// heap fail on demand (`oom()` in the script).
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <csignal>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <new>
#include <thread>

#include "etroll_bus.hpp"
#include "fork_first.hpp"
#include "rollsense/hal/dynamixel/bus.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"
#include "rollsense/last_resort.hpp"
#include "runtime/lua/sandbox.hpp"
#include "runtime/session/session.hpp"
#include "temp_dir.hpp"

namespace {
std::atomic<bool> g_heap_fails{false};
}  // namespace

// malloc/free underneath, consistently: GCC cannot see that the pairs match.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
// Every plain form, so that no pair mixes this heap with the library's (ASan checks).
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    return g_heap_fails.load(std::memory_order_relaxed) ? nullptr : std::malloc(size ? size : 1);
}
void* operator new(std::size_t size) {
    if (void* p = operator new(size, std::nothrow)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return operator new(size, std::nothrow); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace rollsense;
using namespace rollsense::hal::dxl;
using rollsense::testing::read_file;
namespace fs = std::filesystem;

namespace {

// Lua panic: an error raised on the main thread, which no protected call covers
// while the scheduler runs the script's coroutines.
int l_panic(lua_State* L) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
    lua_State* main = lua_tothread(L, -1);
    lua_pushstring(main, "forced by the test");
    return lua_error(main);
}

int l_terminate(lua_State*) { std::terminate(); }

// Ctrl-C, then stuck outside any device call (no hook reaches a C function): the cancel watchdog ends the run.
int l_stuck(lua_State*) {
    ::raise(SIGINT);
    for (;;) ::pause();
}

// The heap fails from now on; it serves again once the last resort has run,
// as when the allocation that failed was one huge request.
void heap_back(void*) noexcept { g_heap_fails = false; }
int l_oom(lua_State*) {
    static const int slot = add_last_resort(&heap_back, nullptr);
    (void)slot;
    g_heap_fails = true;
    return 0;
}

struct Outcome {
    int exit_code = -1;  // -1: killed by a signal
    std::string run_info;
    bool torque[5] = {};
    double current_ma[5] = {};
};

Outcome clamp_then(const char* name, lua_CFunction fault) {
    const testing::TempDir tmp("rollsense-crash");
    std::ofstream(tmp.path() / "script.lua") << "local rs = require 'rollsense'\n"
                                                "local etroll = require 'etroll'\n"
                                                "rs.trial{ object = 'C2', speed = 10, repetition = 1 }\n"
                                                "etroll.open()\n"
                                                "etroll.clamp()\n"
                                             << name << "()\n"
                                             << "rs.wait(500)\n"
                                                "error('still running after " << name << "()')\n";
    runtime::SessionOptions o;
    o.script = tmp.path() / "script.lua";
    o.profile = "etroll-emulated";
    o.share_dir = ROLLSENSE_SHARE_DIR;
    o.out_dir = tmp.path() / "out";
    o.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    o.sandbox.cancel_grace_ms = 300;

    // Forked before the emulator's serving thread exists (fork_first.hpp says why).
    testing::ForkedFirst child([&](const std::string& device) {
        ::alarm(60);
        if (!o.settings.add("dxl_device=" + device).ok()) return 4;
        runtime::Session session(o);
        if (!session.prepare().ok()) return 3;
        lua_State* L = session.sandbox().state();
        lua_rawgeti(L, LUA_REGISTRYINDEX, session.sandbox().env_ref());
        lua_pushcfunction(L, fault);
        lua_setfield(L, -2, name);
        lua_pop(L, 1);
        const auto summary = session.run();
        return summary.status.ok() ? 0 : 1;
    });
    auto emu = etroll_bus::start();
    child.hand_over(emu->device());
    const int status = child.wait();
    Outcome out;
    if (WIFEXITED(status)) out.exit_code = WEXITSTATUS(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the serving thread takes the last bytes
    if (fs::exists(tmp.path() / "out" / "run-info.csv")) out.run_info = read_file(tmp.path() / "out" / "run-info.csv");
    auto port = hal::SerialPort::open(emu->device(), 1'000'000);
    REQUIRE(port.ok());
    Bus client(std::move(port).value(), BusOptions{std::chrono::milliseconds(100), 3});
    for (std::uint8_t id : {1, 2, 3, 4}) {
        auto torque = client.read_value(id, addr::torque_enable, 1);
        auto current = client.read_value(id, addr::present_current, 2);
        REQUIRE(torque.ok());
        REQUIRE(current.ok());
        const auto* model = emu->with_bus([id](BusEmulator& b) { return &b.servo(id)->model(); });
        out.torque[id] = *torque != 0;
        out.current_ma[id] = std::abs(current_units_to_ma(*model, *current));
    }
    return out;
}

void check_every_servo_released(const Outcome& r) {
    for (int id : {1, 2, 3, 4}) {
        INFO("servo " << id);
        CHECK_FALSE(r.torque[id]);
        CHECK(r.current_ma[id] <= 20.0);  // the pushing finger no longer squeezes
    }
}

}  // namespace

TEST_CASE("a Lua panic mid-clamp: the prepared torque-off reaches every servo, run-info says so", "[safety][crash]") {
    const auto r = clamp_then("panic", l_panic);
    INFO(r.run_info);
    CHECK(r.exit_code == 134);
    check_every_servo_released(r);
    CHECK_THAT(r.run_info, Catch::Contains("Lua panic") && Catch::Contains("forced by the test") &&
                               Catch::Contains("last-resort actions sent"));
}

TEST_CASE("std::terminate mid-clamp: the prepared torque-off reaches every servo, run-info says so", "[safety][crash]") {
    const auto r = clamp_then("terminate", l_terminate);
    INFO(r.run_info);
    CHECK(r.exit_code == 134);
    check_every_servo_released(r);
    CHECK_THAT(r.run_info, Catch::Contains("std::terminate"));
}

TEST_CASE("the heap fails mid-clamp: the prepared torque-off first, then the run ends recorded", "[safety][crash]") {
    const auto r = clamp_then("oom", l_oom);
    INFO(r.run_info);
    CHECK(r.exit_code == 1);  // run() returned the failure: shutdown and run-info ran after the last resort
    check_every_servo_released(r);
    // The bus's torque-off packets and the test's "heap is back".
    CHECK_THAT(r.run_info, Catch::Contains("status,limit violation: out of memory (std::bad_alloc) during the "
                                           "run; 2 last-resort actions sent"));
}

TEST_CASE("a script stuck after Ctrl-C mid-clamp: the watchdog releases every servo, as a normal end does",
          "[safety][crash][watchdog]") {
    const auto r = clamp_then("stuck", l_stuck);
    INFO(r.run_info);
    CHECK(r.exit_code == 130);
    check_every_servo_released(r);  // before: held in place, the pushing finger still squeezing
    CHECK_THAT(r.run_info, Catch::Contains("did not stop within 300 ms"));
}
