// Issue 22, failure 1, on the Dynamixel bus: the sensing finger's servo stops
// answering while the pushing finger clamps the object with 120 mA. The
// kernel's safe state must still reach every servo that answers, which is read
// back over the bus afterwards by a fresh client, as a person at the rig
// would check. The robot runs period by period as the scheduler does, the
// emulated servos move only when the test advances them (deterministic, fast).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <thread>

#include "rollsense/hal/dynamixel/bus.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"
#include "runtime/plugin/plugin_registry.hpp"
#include "runtime/profile/profile.hpp"
#include "runtime/robot/robot.hpp"

using namespace rollsense;
using namespace rollsense::hal::dxl;
using namespace rollsense::runtime;

namespace {

// A holding servo is not pushing: what it draws at rest is far below this.
constexpr double kSafeCurrentMa = 20.0;

Profile etroll_on(const std::string& device, bool pusher_torque_off) {
    Profile p;
    p.name = "dxl-fault-test";
    p.path = "dxl-fault-test (built in C++)";
    p.virtual_clock = true;
    p.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    p.devices.push_back(
        {"hand", "dynamixel",
         {{"device", device},
          {"baud", std::int64_t{57600}},
          {"ids", std::vector<std::int64_t>{1, 2, 3, 4}},
          {"names", std::vector<std::string>{"sensing_finger", "pushing_finger", "palm", "winch"}},
          {"models", std::vector<std::string>{"XM430-W350", "XM430-W350", "XM430-W350", "XL330-M288"}},
          {"units", std::vector<std::string>{"deg", "deg", "mm", "mm"}},
          {"modes", std::vector<std::string>{"position", "position", "position", "extended_position"}},
          {"radius", std::vector<double>{0, 0, 10, 8}},
          {"ratio", std::vector<double>{1, 1, 2, 1}},
          {"offsets", std::vector<double>{0, 0, 65, 0}},
          {"min", std::vector<double>{-90, -90, 30, -500}},
          {"max", std::vector<double>{90, 90, 100, 500}},
          {"max_current", std::vector<double>{400, 400, 400, 300}},
          {"timeout_ms", std::int64_t{30}},
          {"retries", std::int64_t{1}}}});
    for (auto [name, lo, hi] : {std::tuple{"sensing_finger", -60.0, 60.0}, std::tuple{"pushing_finger", -80.0, 60.0},
                                std::tuple{"palm", 40.0, 100.0}, std::tuple{"winch", -80.0, 300.0}}) {
        JointLimit l;
        l.name = name;
        l.min = lo;
        l.max = hi;
        l.max_velocity = 60;
        l.max_current = 400;
        l.safe_torque_off = pusher_torque_off && std::string(name) == "pushing_finger";
        p.joints.push_back(l);
    }
    return p;
}

struct ReadBack {
    bool torque = false;
    int mode = -1;
    double current_ma = 0;
    bool moving = false;
};

// Clamp, roll, then `kind` strikes servo 1 (the sensing finger); the robot
// fails in that period and is made safe; then a new client reads servos 2-4 back.
std::map<int, ReadBack> clamp_roll_and_fail_servo_1(bool pusher_torque_off, FaultKind kind, Status& failure) {
    std::vector<ServoSetup> servos = etroll_servos();
    servos[1].start_degrees = -66.0;
    servos[1].contact_degrees = -44.0;  // the object, in the pushing finger's way
    BusEmulator bus;
    for (const auto& s : servos) bus.add_servo(s);
    auto emu = PtyBusEmulator::start(std::move(bus), {false, 0});
    REQUIRE(emu.ok());
    auto step = [&](double dt) {
        (*emu)->with_bus([dt](BusEmulator& b) {
            b.advance(dt);
            return 0;
        });
    };

    {
        const Profile profile = etroll_on((*emu)->device(), pusher_torque_off);
        PluginRegistry registry{PluginRegistry::default_search_path(profile.plugin_path)};
        auto created = Robot::create(profile, registry, ROLLSENSE_SHARE_DIR);
        INFO((created.ok() ? std::string() : created.error().message));
        REQUIRE(created.ok());
        auto& robot = **created;
        REQUIRE(robot.activate(0.0).ok());
        JointCommand push;
        push.mode = ControlMode::current;
        push.current = 120;  // share/lua/etroll.lua's clamp current
        REQUIRE(robot.command_joint(*robot.find_joint("pushing_finger"), push).ok());
        double t = 0;
        for (int period = 0; period < 200; ++period) {  // 2 s: the finger reaches the object
            t += 0.01;
            step(0.01);
            REQUIRE(robot.control_tick(t, 0.01).ok());
        }
        REQUIRE(std::abs(robot.find_joint("pushing_finger")->state.current) > 100);  // squeezing
        JointCommand roll = hold_command(*robot.find_joint("sensing_finger"));
        roll.position = 40;
        roll.profile_velocity = 20;
        REQUIRE(robot.command_joint(*robot.find_joint("sensing_finger"), roll).ok());
        for (int period = 0; period < 50; ++period) {
            t += 0.01;
            step(0.01);
            REQUIRE(robot.control_tick(t, 0.01).ok());
        }
        REQUIRE(robot.find_joint("sensing_finger")->state.moving);  // mid-roll

        (*emu)->with_bus([kind](BusEmulator& b) {
            b.schedule({1, kind, b.elapsed()});  // due at the next advance
            return 0;
        });
        t += 0.01;
        step(0.01);
        failure = robot.control_tick(t, 0.01);
        REQUIRE_FALSE(failure.ok());
        robot.safe_state(t);  // as Scheduler::run does, in the same period
        robot.shutdown(t);    // and Session::run at the end (the safe state once more)
        // A SYNC_WRITE has no reply: let the serving thread take the last bytes
        // before the servos move on, as a wire would deliver them.
        auto* handle = dynamic_cast<ActuatorHandle*>(robot.find_device("hand"));
        REQUIRE(handle);
        auto stats = handle->plugin().invoke("statistics", {});
        REQUIRE(stats.ok());
        const auto sent = static_cast<std::uint64_t>(std::get<std::int64_t>(stats->at("bytes_sent")));
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while ((*emu)->bytes_handled() < sent && std::chrono::steady_clock::now() < give_up)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        REQUIRE((*emu)->bytes_handled() >= sent);
        // Less than the Bus Watchdog's 500 ms: this test is about the kernel's
        // safe state, not the servos' own (test_bus_watchdog.cpp).
        step(0.3);
    }  // the robot and its port are gone

    auto port = hal::SerialPort::open((*emu)->device(), 57600);
    REQUIRE(port.ok());
    Bus client(std::move(port).value(), BusOptions{std::chrono::milliseconds(100), 3});
    std::map<int, ReadBack> out;
    for (std::uint8_t id : {2, 3, 4}) {
        ReadBack r;
        auto torque = client.read_value(id, addr::torque_enable, 1);
        auto mode = client.read_value(id, addr::operating_mode, 1);
        auto current = client.read_value(id, addr::present_current, 2);
        auto moving = client.read_value(id, addr::moving, 1);
        REQUIRE(torque.ok());
        REQUIRE(mode.ok());
        REQUIRE(current.ok());
        REQUIRE(moving.ok());
        const auto* model = (*emu)->with_bus([id](BusEmulator& b) { return &b.servo(id)->model(); });
        r.torque = *torque != 0;
        r.mode = *mode;
        r.current_ma = std::abs(current_units_to_ma(*model, *current));
        r.moving = *moving != 0;
        out[id] = r;
    }
    return out;
}

}  // namespace

TEST_CASE("a silent servo mid-roll: the pushing finger stops squeezing and every answering servo holds",
          "[safety][fault]") {
    Status failure;
    auto servo = clamp_roll_and_fail_servo_1(false, FaultKind::silent, failure);
    CHECK(failure.code() == ErrorCode::timeout);
    CHECK_THAT(failure.message(), Catch::Contains("device 'hand'") && Catch::Contains("servo 1"));
    // Profile safe action "hold": position mode at the present position, torque on, no push.
    CHECK(servo[2].torque);
    CHECK(servo[2].mode == static_cast<int>(OperatingMode::position));
    CHECK(servo[2].current_ma <= kSafeCurrentMa);
    for (int id : {3, 4}) {
        INFO("servo " << id);
        CHECK(servo[id].torque);
        CHECK_FALSE(servo[id].moving);
        CHECK(servo[id].current_ma <= kSafeCurrentMa);
    }
}

TEST_CASE("a silent servo mid-roll: a pushing finger whose safe action is torque off is released",
          "[safety][fault]") {
    Status failure;
    auto servo = clamp_roll_and_fail_servo_1(true, FaultKind::silent, failure);
    CHECK_FALSE(failure.ok());
    CHECK_FALSE(servo[2].torque);
    CHECK(servo[2].current_ma <= kSafeCurrentMa);
    CHECK(servo[3].torque);
}

TEST_CASE("every injected fault kind on one servo: a typed error naming it, the others made safe",
          "[safety][fault]") {
    for (auto [kind, code] : {std::pair{FaultKind::hardware_error, ErrorCode::hardware_fault},
                              std::pair{FaultKind::corrupt, ErrorCode::protocol_error},
                              std::pair{FaultKind::slow, ErrorCode::timeout}}) {
        INFO("fault " << to_string(kind));
        Status failure;
        auto servo = clamp_roll_and_fail_servo_1(false, kind, failure);
        INFO(failure.message());
        CHECK(failure.code() == code);
        CHECK_THAT(failure.message(), Catch::Contains("servo 1"));
        CHECK(servo[2].torque);
        CHECK(servo[2].mode == static_cast<int>(OperatingMode::position));
        CHECK(servo[2].current_ma <= kSafeCurrentMa);
        for (int id : {3, 4}) {
            INFO("servo " << id);
            CHECK(servo[id].torque);
            CHECK_FALSE(servo[id].moving);
        }
    }
}
