// Per-model units and conversions (docs/hardware.md §4).
#include <catch2/catch.hpp>

#include "rollsense/hal/dynamixel/control_table.hpp"

using namespace rollsense::hal::dxl;

TEST_CASE("models are known by name and by model number") {
    REQUIRE(find_model("XM430-W350"));
    REQUIRE(find_model("XL330-M288"));
    CHECK(find_model("XM430-W350")->model_number == 1020);
    CHECK(find_model("XL330-M288")->model_number == 1200);
    CHECK(find_model(std::uint16_t{1020})->name == "XM430-W350");
    CHECK(find_model("AX-12A") == nullptr);
    CHECK(find_model(std::uint16_t{12}) == nullptr);
}

TEST_CASE("position ticks <-> degrees: 4096 ticks per turn, 0 deg at tick 2048") {
    CHECK(ticks_to_degrees(2048) == Approx(0.0));
    CHECK(ticks_to_degrees(3072) == Approx(90.0));
    CHECK(ticks_to_degrees(0) == Approx(-180.0));
    CHECK(ticks_to_degrees(2048 + 4096 * 3) == Approx(1080.0));  // extended position: multi-turn
    CHECK(degrees_to_ticks(-44.0) == 2048 - 501);                 // 44 * 4096/360 = 500.6
    CHECK(degrees_to_ticks(0.088) == 2049);
    for (int t = -5000; t < 9000; t += 37) CHECK(degrees_to_ticks(ticks_to_degrees(t)) == t);
}

TEST_CASE("velocity units <-> rev/min and deg/s: 0.229 rev/min per unit") {
    CHECK(velocity_units_to_rpm(10) == Approx(2.29));
    CHECK(velocity_units_to_rpm(15) == Approx(3.435));
    CHECK(velocity_units_to_rpm(20) == Approx(4.58));
    CHECK(velocity_units_to_deg_s(10) == Approx(13.74));
    CHECK(deg_s_to_velocity_units(13.74) == Approx(10.0));
    CHECK(rpm_to_velocity_units(45.8) == Approx(200.0));
}

TEST_CASE("acceleration units <-> deg/s^2: 214.577 rev/min^2 per unit") {
    CHECK(acceleration_units_to_deg_s2(1) == Approx(21.4577));
    CHECK(deg_s2_to_acceleration_units(acceleration_units_to_deg_s2(37)) == Approx(37.0));
}

TEST_CASE("current units <-> mA differ per model") {
    const auto& xm = *find_model("XM430-W350");
    const auto& xl = *find_model("XL330-M288");
    CHECK(current_units_to_ma(xm, 100) == Approx(269.0));
    CHECK(current_units_to_ma(xl, 100) == Approx(100.0));
    CHECK(ma_to_current_units(xm, 1193 * 2.69) == Approx(1193.0));
    CHECK(xm.max_current_limit == 1193);
    CHECK(xl.max_current_limit == 1750);
}

TEST_CASE("baud rate index <-> bits per second") {
    CHECK(baud_from_index(1) == 57600u);
    CHECK(baud_from_index(3) == 1000000u);
    CHECK(baud_from_index(7) == 4500000u);
    CHECK_FALSE(baud_from_index(8).has_value());
    CHECK(index_from_baud(57600) == std::uint8_t{1});
    CHECK_FALSE(index_from_baud(12345).has_value());
}

// Independent hardware review item 4: the driver, the emulator and the tests
// all take their addresses from addr::, so a wrong one would pass everywhere
// and move a real servo wrongly. Pinned here as the literal numbers of the
// X-series e-Manual (XM430-W350 / XL330-M288 control table); those marked *
// are also in the table of docs/hardware.md §4.
TEST_CASE("control table addresses are the e-Manual's numbers") {
    CHECK(addr::model_number == 0);            // *
    CHECK(addr::model_information == 2);
    CHECK(addr::firmware_version == 6);
    CHECK(addr::id == 7);                      // *
    CHECK(addr::baud_rate == 8);               // *
    CHECK(addr::return_delay_time == 9);       // *
    CHECK(addr::drive_mode == 10);
    CHECK(addr::operating_mode == 11);         // *
    CHECK(addr::homing_offset == 20);
    CHECK(addr::moving_threshold == 24);
    CHECK(addr::temperature_limit == 31);
    CHECK(addr::max_voltage_limit == 32);
    CHECK(addr::min_voltage_limit == 34);
    CHECK(addr::pwm_limit == 36);
    CHECK(addr::current_limit == 38);          // *
    CHECK(addr::velocity_limit == 44);         // *
    CHECK(addr::max_position_limit == 48);     // *
    CHECK(addr::min_position_limit == 52);     // *
    CHECK(addr::shutdown == 63);
    CHECK(addr::torque_enable == 64);          // *
    CHECK(addr::led == 65);
    CHECK(addr::status_return_level == 68);
    CHECK(addr::registered_instruction == 69);
    CHECK(addr::hardware_error_status == 70);  // *
    CHECK(addr::bus_watchdog == 98);           // *
    CHECK(addr::goal_pwm == 100);
    CHECK(addr::goal_current == 102);          // *
    CHECK(addr::goal_velocity == 104);         // *
    CHECK(addr::profile_acceleration == 108);  // *
    CHECK(addr::profile_velocity == 112);      // *
    CHECK(addr::goal_position == 116);         // *
    CHECK(addr::realtime_tick == 120);
    CHECK(addr::moving == 122);                // *
    CHECK(addr::moving_status == 123);
    CHECK(addr::present_pwm == 124);
    CHECK(addr::present_current == 126);       // *
    CHECK(addr::present_velocity == 128);      // *
    CHECK(addr::present_position == 132);      // *
    CHECK(addr::velocity_trajectory == 136);
    CHECK(addr::position_trajectory == 140);
    CHECK(addr::present_input_voltage == 144); // *
    CHECK(addr::present_temperature == 146);   // *
    // Operating Mode (11) values: *
    CHECK(static_cast<int>(OperatingMode::current) == 0);
    CHECK(static_cast<int>(OperatingMode::velocity) == 1);
    CHECK(static_cast<int>(OperatingMode::position) == 3);
    CHECK(static_cast<int>(OperatingMode::extended_position) == 4);
    CHECK(static_cast<int>(OperatingMode::current_based_position) == 5);
    CHECK(static_cast<int>(OperatingMode::pwm) == 16);
}

TEST_CASE("the per-period blocks cover the items they must") {
    // SYNC_WRITE: Goal Current (102, 2) .. Goal Position (116, 4).
    CHECK(kCommandBlockAddress == 102);
    CHECK(kCommandBlockLength == 18);
    // SYNC_READ: Moving (122, 1) .. Present Position (132, 4).
    CHECK(kStateBlockAddress == 122);
    CHECK(kStateBlockLength == 14);
}
