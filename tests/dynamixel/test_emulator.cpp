// The servo emulator's control table rules and motion model, in-process.
#include <catch2/catch.hpp>

#include "rollsense/hal/dynamixel/bus_emulator.hpp"
#include "rollsense/etroll_hand/clamped_object.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"

#include <cmath>

using namespace rollsense::hal::dxl;
using rollsense::etroll::ClampedObject;
using rollsense::etroll::clamp_object;
using rollsense::etroll::pushing_contact_degrees;

namespace {

Bytes le(std::int64_t v, std::size_t n) {
    Bytes b;
    put_le(b, v, n);
    return b;
}

ServoSetup setup(std::uint8_t id, const ModelInfo* model, double start = 0.0,
                 OperatingMode mode = OperatingMode::position, std::optional<double> contact = std::nullopt) {
    return ServoSetup{id, model, start, mode, contact, 1};
}

std::uint8_t write(EmulatedServo& s, std::uint16_t a, std::int64_t v, std::size_t n) { return s.write(a, le(v, n)); }

}  // namespace

TEST_CASE("EEPROM items are writable only with torque off, read-only items never") {
    EmulatedServo s(setup(1, find_model("XM430-W350")));
    CHECK(write(s, addr::operating_mode, 4, 1) == 0);
    CHECK(write(s, addr::torque_enable, 1, 1) == 0);
    CHECK(write(s, addr::operating_mode, 3, 1) == static_cast<std::uint8_t>(StatusError::access));
    CHECK(s.mode() == OperatingMode::extended_position);  // a refused write changes nothing
    CHECK(write(s, addr::present_position, 0, 4) == static_cast<std::uint8_t>(StatusError::access));
    CHECK(write(s, addr::model_number, 1, 2) == static_cast<std::uint8_t>(StatusError::access));
}

TEST_CASE("range and limit errors are told apart") {
    EmulatedServo s(setup(1, find_model("XL330-M288")));
    CHECK(write(s, addr::operating_mode, 2, 1) == static_cast<std::uint8_t>(StatusError::data_range));
    CHECK(write(s, addr::baud_rate, 7, 1) == static_cast<std::uint8_t>(StatusError::data_range));  // 4.5M is XM430 only
    CHECK(write(s, addr::current_limit, 1751, 2) == static_cast<std::uint8_t>(StatusError::data_range));
    CHECK(write(s, addr::max_position_limit, 3000, 4) == 0);
    CHECK(write(s, addr::goal_position, 3500, 4) == static_cast<std::uint8_t>(StatusError::data_limit));
    CHECK(write(s, addr::current_limit, 500, 2) == 0);
    CHECK(write(s, addr::goal_current, 600, 2) == static_cast<std::uint8_t>(StatusError::data_limit));
    CHECK(write(s, addr::goal_current, -500, 2) == 0);
    Bytes out;
    CHECK(s.read(140, 10, out) == static_cast<std::uint8_t>(StatusError::data_range));  // past the table
}

TEST_CASE("changing the operating mode resets profiles and goal current") {
    EmulatedServo s(setup(1, find_model("XM430-W350")));
    REQUIRE(write(s, addr::profile_velocity, 10, 4) == 0);
    REQUIRE(write(s, addr::goal_current, 100, 2) == 0);
    REQUIRE(write(s, addr::operating_mode, 5, 1) == 0);
    CHECK(s.item(addr::profile_velocity, 4) == 0);
    CHECK(s.item(addr::goal_current, 2) == 1193);
}

TEST_CASE("a position profile reaches its goal at the profile velocity and reports moving meanwhile") {
    EmulatedServo s(setup(1, find_model("XM430-W350"), -44.0));
    REQUIRE(write(s, addr::profile_velocity, 10, 4) == 0);  // 2.29 rev/min = 13.74 deg/s
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    REQUIRE(write(s, addr::goal_position, degrees_to_ticks(44.0), 4) == 0);
    s.step(1.0);
    CHECK(s.item(addr::moving, 1) == 1);
    CHECK(ticks_to_degrees(s.position_ticks()) == Approx(-44.0 + 13.74).margin(0.2));
    CHECK(s.item(addr::present_velocity, 4) == 10);
    s.step(6.0);  // 88 deg at 13.74 deg/s takes 6.4 s
    CHECK(s.item(addr::moving, 1) == 0);
    CHECK(s.item(addr::present_position, 4) == degrees_to_ticks(44.0));
}

TEST_CASE("profile acceleration shapes a trapezoid") {
    EmulatedServo s(setup(1, find_model("XM430-W350")));
    REQUIRE(write(s, addr::profile_acceleration, 5, 4) == 0);  // 107 deg/s^2
    REQUIRE(write(s, addr::profile_velocity, 50, 4) == 0);     // 68.7 deg/s
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    REQUIRE(write(s, addr::goal_position, degrees_to_ticks(90.0), 4) == 0);
    s.step(0.2);
    // v = a t = 21.46 deg/s after 0.2 s, far below the profile velocity
    CHECK(s.item(addr::present_velocity, 4) == Approx(deg_s_to_velocity_units(21.46)).margin(1.0));
    s.step(5.0);
    CHECK(s.item(addr::present_position, 4) == degrees_to_ticks(90.0));
}

TEST_CASE("without torque the servo does not move, and enabling torque keeps a stale goal (the emulator is strict)") {
    EmulatedServo s(setup(1, find_model("XM430-W350"), 10.0));
    REQUIRE(write(s, addr::goal_position, degrees_to_ticks(-30.0), 4) == 0);
    s.step(1.0);
    CHECK(ticks_to_degrees(s.position_ticks()) == Approx(10.0));
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    s.step(3.0);
    CHECK(ticks_to_degrees(s.position_ticks()) == Approx(-30.0).margin(0.1));
}

TEST_CASE("current mode pushes against the modelled contact with the commanded current") {
    // Pushing finger at -66 deg, object surface at -44 deg.
    EmulatedServo s(setup(2, find_model("XM430-W350"), -66.0, OperatingMode::current, -44.0));
    REQUIRE(write(s, addr::goal_current, 40, 2) == 0);  // 107.6 mA
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    s.step(0.05);
    CHECK(s.item(addr::present_velocity, 4) > 0);
    s.step(3.0);
    CHECK(ticks_to_degrees(s.position_ticks()) == Approx(-44.0).margin(0.01));
    CHECK(s.item(addr::present_current, 2) == 40);
    CHECK(s.item(addr::present_velocity, 4) == 0);
    CHECK(s.item(addr::moving, 1) == 0);
    // Reversing the current pulls it away from the contact.
    REQUIRE(write(s, addr::goal_current, -40, 2) == 0);
    s.step(0.2);
    CHECK(ticks_to_degrees(s.position_ticks()) < -44.5);
}

TEST_CASE("current-based position stops at the contact with the goal current as ceiling") {
    EmulatedServo s(setup(2, find_model("XL330-M288"), 0.0, OperatingMode::current_based_position, 20.0));
    REQUIRE(write(s, addr::goal_current, 300, 2) == 0);
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    REQUIRE(write(s, addr::goal_position, degrees_to_ticks(60.0), 4) == 0);
    s.step(3.0);
    CHECK(ticks_to_degrees(s.position_ticks()) == Approx(20.0).margin(0.01));
    CHECK(s.item(addr::present_current, 2) == 300);
    CHECK(s.item(addr::moving, 1) == 0);
}

TEST_CASE("a hardware error turns torque off, sets the alert bit, refuses torque, and only reboot clears it") {
    EmulatedServo s(setup(1, find_model("XM430-W350")));
    REQUIRE(write(s, addr::torque_enable, 1, 1) == 0);
    s.raise_hardware_error(hw_error::overload);
    CHECK_FALSE(s.torque_enabled());
    CHECK(s.alert_bits() == kAlertBit);
    CHECK(write(s, addr::torque_enable, 1, 1) == static_cast<std::uint8_t>(StatusError::result_fail));
    s.reboot();
    CHECK(s.hardware_error() == 0);
    CHECK(write(s, addr::torque_enable, 1, 1) == 0);
}

TEST_CASE("reboot keeps EEPROM and resets RAM") {
    EmulatedServo s(setup(1, find_model("XM430-W350")));
    REQUIRE(write(s, addr::operating_mode, 4, 1) == 0);
    REQUIRE(write(s, addr::profile_velocity, 33, 4) == 0);
    s.reboot();
    CHECK(s.mode() == OperatingMode::extended_position);
    CHECK(s.item(addr::profile_velocity, 4) == 0);
    CHECK(s.id() == 1);
}

TEST_CASE("the bus answers PING, READ and WRITE and ignores other ids") {
    BusEmulator bus;
    for (const auto& s : etroll_servos()) bus.add_servo(s);
    auto r = bus.receive(build_instruction(4, Instruction::ping, {}));
    REQUIRE(r.size() == 1);
    PacketParser p;
    p.feed(r[0]);
    auto pk = p.next();
    REQUIRE(pk);
    CHECK(pk->packet.id == 4);
    CHECK(get_le(pk->packet.params.data(), 2) == 1200);  // the winch is an XL330
    CHECK(bus.receive(build_instruction(9, Instruction::ping, {})).empty());
    auto all = bus.receive(build_instruction(kBroadcastId, Instruction::ping, {}));
    CHECK(all.size() == 4);
    // An instruction this emulator does not implement gets an instruction error.
    auto bulk = bus.receive(build_instruction(1, Instruction::reg_write, Bytes{0x40, 0x00, 0x01}));
    REQUIRE(bulk.size() == 1);
    p.feed(bulk[0]);
    CHECK(p.next()->packet.error_code() == static_cast<std::uint8_t>(StatusError::instruction));
}

TEST_CASE("a corrupted instruction addressed to a servo gets a CRC error status") {
    BusEmulator bus;
    bus.add_servo(setup(1, find_model("XM430-W350")));
    Bytes pk = build_instruction(1, Instruction::read, Bytes{0x84, 0x00, 0x04, 0x00});
    pk[8] ^= 0x10;
    auto r = bus.receive(pk);
    REQUIRE(r.size() == 1);
    PacketParser p;
    p.feed(r[0]);
    CHECK(p.next()->packet.error_code() == static_cast<std::uint8_t>(StatusError::crc));
    CHECK(bus.crc_errors_seen() == 1);
}

TEST_CASE("servo specs parse and explain what is wrong") {
    auto s = parse_servo_spec("2:XM430-W350:-66:current:-44");
    REQUIRE(s.ok());
    CHECK(s->id == 2);
    CHECK(s->start_degrees == -66.0);
    CHECK(s->mode == OperatingMode::current);
    CHECK(s->contact_degrees == -44.0);
    CHECK(parse_servo_spec("1:XM430-W350").ok());
    CHECK(parse_servo_spec("1:AX-12").error().message.find("unknown model") != std::string::npos);
    CHECK(parse_servo_spec("300:XM430-W350").error().message.find("bad id") != std::string::npos);
    CHECK(parse_servo_spec("1:XM430-W350:0:spin").error().message.find("operating mode") != std::string::npos);
}

TEST_CASE("the clamped object's contact angle is parallel at w = d / cos(theta), more open with a narrower palm") {
    ClampedObject o;  // W 24 + T 42 = d 66 mm, lever 70 mm, palm 0.349 mm/deg about 65 mm
    const double deg = 180.0 / M_PI;
    const auto palm_degrees_for = [&](double width) { return (width - o.palm_centre_mm) / o.palm_mm_per_degree; };
    for (double theta : {-44.0, -20.0, 0.0, 30.0, 44.0}) {
        const double parallel = o.effective_width_mm() / std::cos(theta / deg);
        CHECK(pushing_contact_degrees(o, theta, palm_degrees_for(parallel)) == Approx(theta).margin(1e-9));
        // 5 mm of misfit over a 70 mm lever: about 3 deg (less cos θ).
        CHECK(pushing_contact_degrees(o, theta, palm_degrees_for(parallel - 5.0)) < theta - 2.5);
        CHECK(pushing_contact_degrees(o, theta, palm_degrees_for(parallel + 5.0)) > theta + 2.5);
    }
}

TEST_CASE("on a bus with a clamped object, the palm width sets where the clamping finger stops") {
    BusEmulator bus;
    bus.add_servo(setup(1, find_model("XM430-W350"), -44.0));
    bus.add_servo(setup(2, find_model("XM430-W350"), -66.0, OperatingMode::current));
    bus.add_servo(setup(3, find_model("XM430-W350"), 0.0));  // palm at its centre: 65 mm
    ClampedObject o;
    REQUIRE(clamp_object(bus, o).ok());
    for (std::uint8_t id : {1, 2, 3}) REQUIRE(write(*bus.servo(id), addr::torque_enable, 1, 1) == 0);
    auto& pushing = *bus.servo(2);
    REQUIRE(write(pushing, addr::goal_current, 45, 2) == 0);  // 121 mA, the Table I clamp
    bus.advance(1.0);
    // Palm too narrow for parallel fingers at -44 deg: held open at about -60 deg.
    const double narrow = ticks_to_degrees(pushing.position_ticks());
    const double sensing = ticks_to_degrees(bus.servo(1)->position_ticks());  // -44 to the tick
    CHECK(narrow == Approx(pushing_contact_degrees(o, sensing, 0.0)).margin(0.01));
    CHECK(narrow < -58.0);
    CHECK(pushing.item(addr::present_current, 2) == 45);  // pressing on the object
    // Open the palm to the parallel width (d / cos 44 deg, about 92 mm): the finger follows the object to -44 deg.
    const double parallel_palm_degrees = (o.effective_width_mm() / std::cos(44.0 * M_PI / 180.0) - 65.0) /
                                         o.palm_mm_per_degree;
    REQUIRE(write(*bus.servo(3), addr::goal_position, degrees_to_ticks(parallel_palm_degrees), 4) == 0);
    bus.advance(2.0);
    CHECK(ticks_to_degrees(pushing.position_ticks()) == Approx(-44.0).margin(0.1));
    // Closing the palm again pushes the finger back open through the object.
    REQUIRE(write(*bus.servo(3), addr::goal_position, degrees_to_ticks(0.0), 4) == 0);
    bus.advance(2.0);
    CHECK(ticks_to_degrees(pushing.position_ticks()) == Approx(narrow).margin(0.05));
}

TEST_CASE("the clamped object takes its geometry from the hand, and needs its three servos on the bus") {
    ClampedObject o;
    // The defaults are the simulation's calibrated hand (one home: HandGeometry).
    CHECK(o.hand.finger_offset_sum == rollsense::etroll::HandGeometry{}.finger_offset_sum);
    CHECK(o.effective_width_mm() == Approx(rollsense::etroll::kDefaultEmulatedObjectWidth + o.hand.finger_offset_sum));
    // A wider object needs a wider palm for the same contact angle.
    ClampedObject wide = o;
    wide.object_width_mm += 10.0;
    CHECK(pushing_contact_degrees(wide, 0.0, 0.0) == Approx(pushing_contact_degrees(o, 0.0, 0.0) -
                                                              10.0 * 180.0 / M_PI / o.hand.array_distance));
    BusEmulator bus;
    bus.add_servo(setup(1, find_model("XM430-W350"), 0.0));
    bus.add_servo(setup(3, find_model("XM430-W350"), 0.0));
    const auto st = clamp_object(bus, o);
    REQUIRE_FALSE(st.ok());
    CHECK(st.message().find("pushing finger (servo 2)") != std::string::npos);
}
