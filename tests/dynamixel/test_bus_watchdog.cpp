// The emulated servo's Bus Watchdog (address 98) and its timed fault injection.
#include <catch2/catch.hpp>

#include "rollsense/hal/dynamixel/bus_emulator.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/injected_fault.hpp"

using namespace rollsense;
using namespace rollsense::hal::dxl;

namespace {

Bytes le(std::int64_t v, std::size_t n) {
    Bytes b;
    put_le(b, v, n);
    return b;
}
std::uint8_t write(EmulatedServo& s, std::uint16_t a, std::int64_t v, std::size_t n) { return s.write(a, le(v, n)); }
constexpr auto kAccess = static_cast<std::uint8_t>(hal::dxl::StatusError::access);

}  // namespace

TEST_CASE("the Bus Watchdog trips after its time without an instruction, holds, and clears with 0") {
    EmulatedServo s(ServoSetup{1, find_model("XM430-W350"), 0.0, OperatingMode::position, std::nullopt, 1});
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    CHECK(write(s, addr::bus_watchdog, 128, 1) == static_cast<std::uint8_t>(hal::dxl::StatusError::data_range));
    REQUIRE(write(s, addr::bus_watchdog, 25, 1) == 0);  // 500 ms
    REQUIRE(write(s, addr::profile_velocity, 50, 4) == 0);
    REQUIRE(write(s, addr::goal_position, 3000, 4) == 0);
    s.heard_instruction();
    s.step(0.45);
    CHECK_FALSE(s.watchdog_tripped());
    s.heard_instruction();  // traffic keeps it quiet
    s.step(0.45);
    CHECK_FALSE(s.watchdog_tripped());
    s.step(0.1);
    REQUIRE(s.watchdog_tripped());
    CHECK(s.item(addr::bus_watchdog, 1) == -1);
    const double stopped_at = s.position_ticks();
    s.step(1.0);
    CHECK(s.position_ticks() == Approx(stopped_at).margin(40));  // decelerates, then holds
    const double held = s.position_ticks();
    s.step(1.0);
    CHECK(s.position_ticks() == Approx(held).margin(1e-6));
    CHECK(s.torque_enabled());
    CHECK(write(s, addr::goal_position, 1000, 4) == kAccess);  // goals read-only until cleared
    CHECK(write(s, addr::bus_watchdog, 0, 1) == 0);
    CHECK_FALSE(s.watchdog_tripped());
    CHECK(write(s, addr::goal_position, 1000, 4) == 0);
}

TEST_CASE("a tripped Bus Watchdog in current mode stops the push, with torque off it never trips") {
    EmulatedServo s(ServoSetup{2, find_model("XM430-W350"), 0.0, OperatingMode::current, 10.0, 1});
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    REQUIRE(write(s, addr::goal_current, 45, 2) == 0);  // about 121 mA
    REQUIRE(write(s, addr::bus_watchdog, 10, 1) == 0);  // 200 ms
    s.heard_instruction();
    s.step(0.15);
    CHECK(std::abs(s.current_ma()) > 100);  // pushing on the contact
    s.step(0.1);
    REQUIRE(s.watchdog_tripped());
    s.step(0.05);
    CHECK(std::abs(s.current_ma()) < 1.0);

    EmulatedServo off(ServoSetup{3, find_model("XM430-W350"), 0.0, OperatingMode::position, std::nullopt, 1});
    REQUIRE(write(off, addr::bus_watchdog, 1, 1) == 0);
    off.step(5.0);
    CHECK_FALSE(off.watchdog_tripped());
}

TEST_CASE("instruction packets reaching a servo restart its watchdog count, broadcast reaches all") {
    BusEmulator bus;
    for (std::uint8_t id : {1, 2}) bus.add_servo(ServoSetup{id, nullptr, 0.0, OperatingMode::position, std::nullopt, 1});
    for (std::uint8_t id : {1, 2}) {
        REQUIRE(bus.servo(id)->write(addr::torque_enable, le(1, 1)) == 0);
        REQUIRE(bus.servo(id)->write(addr::bus_watchdog, le(5, 1)) == 0);  // 100 ms
    }
    for (int i = 0; i < 10; ++i) {
        bus.advance(0.05);
        (void)bus.handle(Packet{1, static_cast<std::uint8_t>(Instruction::ping), 0, {}});  // servo 1 only
    }
    CHECK_FALSE(bus.servo(1)->watchdog_tripped());
    CHECK(bus.servo(2)->watchdog_tripped());
}

TEST_CASE("injected faults parse from ID:KIND:AFTER_S and strike on the emulated clock") {
    auto f = parse_injected_fault("3:hardware-error:1.5");
    REQUIRE(f.ok());
    CHECK(f->id == 3);
    CHECK(f->kind == FaultKind::hardware_error);
    CHECK(f->after_s == 1.5);
    for (const char* bad : {"3:silent", "x:silent:1", "300:silent:1", "3:melt:1", "3:slow:-1", "3:slow:nan", ""}) {
        INFO(bad);
        auto r = parse_injected_fault(bad);
        REQUIRE_FALSE(r.ok());
        CHECK_THAT(r.error().message, Catch::Contains(std::string("fault '") + bad + "'"));
    }
    BusEmulator bus;
    bus.add_servo(ServoSetup{3, nullptr, 0.0, OperatingMode::position, std::nullopt, 1});
    bus.schedule(*f);
    bus.schedule({3, FaultKind::slow, 2.0});
    bus.advance(1.4);
    CHECK(bus.servo(3)->hardware_error() == 0);
    bus.advance(0.2);
    CHECK(bus.servo(3)->hardware_error() == hw_error::overload);
    CHECK(bus.late_by(3).count() == 0);
    bus.advance(0.5);
    CHECK(bus.late_by(3) == kLateBy);
}
