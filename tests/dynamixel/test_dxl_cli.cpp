// `rollsense dxl` against the servo emulator on a pseudo-terminal: the bring-up
// steps docs/dynamixel.md gives for a fresh servo (id 1, 57600 baud).
#include <catch2/catch.hpp>

#include <regex>

#include "etroll_bus.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"
#include "run_command.hpp"

using namespace rollsense;
using namespace rollsense::hal::dxl;

namespace {

std::unique_ptr<PtyBusEmulator> fresh_servo() {
    BusEmulator bus;
    bus.add_servo(ServoSetup{});  // as from the factory: id 1, 57600 baud
    auto emu = PtyBusEmulator::start(std::move(bus));
    REQUIRE(emu.ok());
    return std::move(emu).value();
}

}  // namespace

TEST_CASE("dxl set-id succeeds although the servo answers as its new id", "[dxl][cli]") {
    auto emu = fresh_servo();
    const auto set = testing::run_rollsense("dxl set-id --device " + emu->device() + " --id 1 --new-id 3");
    INFO(set.output);
    CHECK(set.status == 0);
    CHECK(set.output.find("id 1: id is now 3") != std::string::npos);
    CHECK(emu->with_bus([](BusEmulator& b) { return b.ids(); }) == std::vector<std::uint8_t>{3});

    const auto scan = testing::run_rollsense("dxl scan --device " + emu->device() + " --ids 1-5");
    INFO(scan.output);
    CHECK(scan.status == 0);
    CHECK(std::regex_search(scan.output, std::regex(R"(id +3 +XM430-W350)")));
}

TEST_CASE("dxl set-id still fails when no servo answers, old id or new", "[dxl][cli]") {
    auto emu = fresh_servo();
    const auto set = testing::run_rollsense("dxl set-id --device " + emu->device() + " --id 7 --new-id 3");
    INFO(set.output);
    CHECK(set.status == 4);
    CHECK(set.output.find("servo 7 did not answer") != std::string::npos);
    CHECK(emu->with_bus([](BusEmulator& b) { return b.ids(); }) == std::vector<std::uint8_t>{1});
}

TEST_CASE("dxl set-id refuses an id another servo on the bus answers to", "[dxl][cli]") {
    BusEmulator bus;
    for (std::uint8_t id : {2, 4}) {
        ServoSetup s;
        s.id = id;
        bus.add_servo(s);
    }
    auto emu = PtyBusEmulator::start(std::move(bus));
    REQUIRE(emu.ok());
    const auto set = testing::run_rollsense("dxl set-id --device " + (*emu)->device() + " --id 4 --new-id 2");
    INFO(set.output);
    CHECK(set.status == 2);
    CHECK(set.output.find("id 2 is taken: a XM430-W350") != std::string::npos);
    // Nothing written: both servos keep their ids, servo 4's EEPROM untouched.
    CHECK((*emu)->with_bus([](BusEmulator& b) { return b.ids(); }) == std::vector<std::uint8_t>{2, 4});
    CHECK((*emu)->with_bus([](BusEmulator& b) { return b.servo(4)->item(addr::id, 1); }) == 4);
    // Two servos sharing an id garble their replies: only a timeout shows an id is free.
    (*emu)->with_bus([](BusEmulator& b) { b.set_faults(2, {0, -1}); return 0; });
    const auto garbled = testing::run_rollsense("dxl set-id --device " + (*emu)->device() + " --id 4 --new-id 2");
    INFO(garbled.output);
    CHECK(garbled.status == 2);
    CHECK(garbled.output.find("id 2 is taken: a reply that is not a servo's") != std::string::npos);
    CHECK((*emu)->with_bus([](BusEmulator& b) { return b.servo(4)->item(addr::id, 1); }) == 4);
}

TEST_CASE("dxl set-id on the E-TRoll bus: the emulator's clamped object lets a servo leave its role",
          "[dxl][cli]") {
    auto emu = etroll_bus::start();  // the clamp couples servos 1 (sensing), 2 (pushing) and 3 (palm)
    const auto set = testing::run_rollsense("dxl set-id --device " + emu->device() + " --baud 1000000 --id 1 --new-id 7");
    INFO(set.output);
    CHECK(set.status == 0);
    // The emulator moves on in real time (the coupling runs) and still serves the bus.
    const auto scan = testing::run_rollsense("dxl scan --device " + emu->device() + " --baud 1000000 --ids 1-8");
    INFO(scan.output);
    CHECK(scan.status == 0);
    CHECK(std::regex_search(scan.output, std::regex(R"(id +7 +XM430-W350)")));
    CHECK(emu->with_bus([](BusEmulator& b) { return b.ids(); }) == std::vector<std::uint8_t>{7, 2, 3, 4});
}

// Safety review: after a killed run a servo stopped by its Bus Watchdog showed
// only "torque on", like one that holds; `dxl info` says it tripped.
TEST_CASE("dxl info shows the Bus Watchdog: off, its time, or tripped", "[dxl][cli]") {
    auto emu = fresh_servo();
    const auto info = [&] {
        const auto r = testing::run_rollsense("dxl info --device " + emu->device() + " --id 1");
        INFO(r.output);
        CHECK(r.status == 0);
        return r.output;
    };
    CHECK_THAT(info(), Catch::Contains("  bus watchdog     off\n"));
    emu->with_bus([](BusEmulator& b) {
        auto* s = b.servo(1);
        // Its longest time (127 x 20 ms): the emulator runs on the real clock, and a shorter one tripped while the
        // command started under the sanitizers on a loaded machine (CI: "TRIPPED" where "100 ms" was expected).
        Bytes one{1}, longest{127};
        REQUIRE(s->write(addr::torque_enable, one) == 0);
        REQUIRE(s->write(addr::bus_watchdog, longest) == 0);
        return 0;
    });
    CHECK_THAT(info(), Catch::Contains("  bus watchdog     2540 ms\n"));
    emu->with_bus([](BusEmulator& b) {
        b.advance(3.0);  // no instruction for longer than the watchdog: it trips
        return 0;
    });
    CHECK_THAT(info(), Catch::Contains("  bus watchdog     TRIPPED: stopped, ignores goals until a run activates it\n"));
}
