// `rollsense dxl` against the servo emulator on a pseudo-terminal: the bring-up
// steps docs/dynamixel.md gives for a fresh servo (id 1, 57600 baud).
#include <catch2/catch.hpp>

#include <regex>

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
