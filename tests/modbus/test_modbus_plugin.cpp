// The `modbus` actuator against a libmodbus TCP server on 127.0.0.1.
#include <catch2/catch.hpp>

#include <cmath>
#include <thread>

#include "rollsense/testing/conformance.hpp"
#include "log_capture.hpp"
#include "loopback_server.hpp"
#include "modbus_actuator.hpp"

using namespace rollsense;
using rollsense::modbus::ModbusActuator;
using rollsense::testing::ModbusLoopbackServer;

namespace {

// A winch motor driver: holding 0-1 goal (s32, 0.01 mm), 2-3 position (s32),
// 4 status (bit0 moving, bit1 ready), 5 fault code, 6 current (s16, mA),
// 10 enable. Moves at 20 mm/s toward the goal while enabled.
constexpr int kStartCounts = 1234;  // 12.34 mm

std::int32_t s32(const std::vector<std::uint16_t>& r, int at) {
    return static_cast<std::int32_t>((std::uint32_t{r[static_cast<std::size_t>(at)]} << 16) |
                                     r[static_cast<std::size_t>(at) + 1]);
}
void put_s32(std::vector<std::uint16_t>& r, int at, std::int32_t v) {
    r[static_cast<std::size_t>(at)] = static_cast<std::uint16_t>(static_cast<std::uint32_t>(v) >> 16);
    r[static_cast<std::size_t>(at) + 1] = static_cast<std::uint16_t>(static_cast<std::uint32_t>(v) & 0xFFFF);
}

std::unique_ptr<ModbusLoopbackServer> winch_driver() {
    auto server = std::make_unique<ModbusLoopbackServer>(
        16, [pos = double(kStartCounts)](std::vector<std::uint16_t>& h, std::vector<std::uint16_t>&, double dt) mutable {
            const bool enabled = h[10] == 1;
            const double goal = s32(h, 0);
            if (enabled) {
                const double step = 2000.0 * dt;
                pos = std::abs(goal - pos) <= step ? goal : pos + (goal > pos ? step : -step);
            }
            put_s32(h, 2, static_cast<std::int32_t>(std::lround(pos)));
            const bool moving = enabled && std::lround(pos) != std::lround(goal);
            h[4] = static_cast<std::uint16_t>((moving ? 1 : 0) | (enabled ? 2 : 0));
            h[6] = static_cast<std::uint16_t>(moving ? 350 : 20);
        });
    // A previous run left a far-away goal in the driver.
    server->with_registers([](auto& h, auto&) { put_s32(h, 0, 9000); return 0; });
    return server;
}

std::map<std::string, ParamValue> winch_raw(int port) {
    return {
        {"transport", std::string("tcp")},
        {"host", std::string("127.0.0.1")},
        {"port", std::int64_t{port}},
        {"slave", std::int64_t{1}},
        {"timeout_ms", std::int64_t{50}},
        {"retries", std::int64_t{1}},
        {"name", std::string("winch")},
        {"unit", std::string("mm")},
        {"min", -100.0},
        {"max", 200.0},
        {"goal_register", std::int64_t{0}},
        {"goal_format", std::string("s32")},
        {"goal_scale", 0.01},
        {"position_register", std::int64_t{2}},
        {"position_format", std::string("s32")},
        {"position_scale", 0.01},
        {"status_register", std::int64_t{4}},
        {"moving_mask", std::int64_t{1}},
        {"moving_value", std::int64_t{1}},
        {"ready_mask", std::int64_t{2}},
        {"ready_value", std::int64_t{2}},
        {"fault_register", std::int64_t{5}},
        {"current_register", std::int64_t{6}},
        {"activate_register", std::int64_t{10}},
        {"activate_values", std::vector<std::int64_t>{1}},
        {"deactivate_values", std::vector<std::int64_t>{0}},
    };
}

ParamSet validated(const std::map<std::string, ParamValue>& raw) {
    auto p = validate_params(modbus::modbus_schema(), raw, "test profile: devices.winch");
    INFO((p.ok() ? std::string() : p.error().message));
    REQUIRE(p.ok());
    return *p;
}

void configure_and_activate(ModbusActuator& a, int port) {
    REQUIRE(a.on_configure(validated(winch_raw(port)), {}).ok());
    auto st = a.on_activate();
    INFO("on_activate: " << st.message());
    REQUIRE(st.ok());
}

JointCommand goal(double position) {
    JointCommand c;
    c.position = position;
    return c;
}

}  // namespace

TEST_CASE("the modbus plugin passes the actuator conformance suite against a winch driver") {
    auto server = winch_driver();
    testing::ActuatorConformance c;
    c.make = [] { return std::make_unique<ModbusActuator>(); };
    c.params = validated(winch_raw(server->port()));
    c.now = [start = std::chrono::steady_clock::now()] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    c.advance = [](double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); };
    c.position_tolerance = 0.02;
    c.move_fraction = 0.05;  // 15 mm at 20 mm/s
    testing::check_actuator_conformance(c);
}

TEST_CASE("activation writes the present position as the goal before enabling the drive") {
    auto server = winch_driver();
    ModbusActuator a;
    configure_and_activate(a, server->port());
    CHECK(server->with_registers([](auto& h, auto&) { return s32(h, 0); }) == kStartCounts);
    CHECK(server->with_registers([](auto& h, auto&) { return int(h[10]); }) == 1);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::vector<JointState> s(1);
    REQUIRE(a.read(0, s).ok());
    CHECK(s[0].position == Approx(12.34).margin(1e-9));
    CHECK_FALSE(s[0].moving);
    REQUIRE(a.on_deactivate().ok());
    CHECK(server->with_registers([](auto& h, auto&) { return int(h[10]); }) == 0);
}

TEST_CASE("a move is written once, followed, and reported with moving and current") {
    auto server = winch_driver();
    ModbusActuator a;
    configure_and_activate(a, server->port());
    const JointCommand cmd = goal(20.0);
    REQUIRE(a.write(0, std::span(&cmd, 1)).ok());
    const auto after_first = server->requests();
    REQUIRE(a.write(0, std::span(&cmd, 1)).ok());  // unchanged goal: nothing to send
    CHECK(server->requests() == after_first);
    CHECK(server->with_registers([](auto& h, auto&) { return s32(h, 0); }) == 2000);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::vector<JointState> s(1);
    REQUIRE(a.read(0, s).ok());
    CHECK(s[0].moving);
    CHECK(s[0].current == Approx(350.0));
    CHECK(s[0].position > 12.34);
    for (int i = 0; i < 100 && s[0].moving; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        REQUIRE(a.read(0, s).ok());
    }
    CHECK_FALSE(s[0].moving);
    CHECK(s[0].position == Approx(20.0));
    const JointCommand far = goal(500.0);
    CHECK(a.write(0, std::span(&far, 1)).code() == ErrorCode::limit_violation);
}

namespace {

JointCommand torque_off() {
    JointCommand c;
    c.torque_enabled = false;
    return c;
}

int enable_register(ModbusLoopbackServer& server) {
    return server.with_registers([](auto& h, auto&) { return int(h[10]); });
}

}  // namespace

// The kernel's safe state sends torque off to a faulted joint or one whose
// profile says safe = "torque_off": the device's release is written.
TEST_CASE("a torque-off command writes the release (deactivate_values) and keeps the joint released") {
    auto server = winch_driver();
    ModbusActuator a;
    configure_and_activate(a, server->port());
    const JointCommand move = goal(20.0);
    REQUIRE(a.write(0, std::span(&move, 1)).ok());
    REQUIRE(enable_register(*server) == 1);
    const JointCommand off = torque_off();
    auto st = a.write(0, std::span(&off, 1));
    INFO(st.message());
    REQUIRE(st.ok());
    CHECK(enable_register(*server) == 0);
    std::vector<JointState> s(1);
    REQUIRE(a.read(0, s).ok());
    CHECK_FALSE(s[0].torque_enabled);
    // The safe state repeats its command each period: written once.
    const auto after_release = server->requests();
    REQUIRE(a.write(0, std::span(&off, 1)).ok());
    CHECK(server->requests() == after_release);
    // Driving it again needs the activation (handshake) again, not a bare goal.
    auto again = a.write(0, std::span(&move, 1));
    CHECK(again.code() == ErrorCode::state_error);
    CHECK(again.message().find("activate") != std::string::npos);
    REQUIRE(a.on_deactivate().ok());
    REQUIRE(a.on_activate().ok());
    CHECK(enable_register(*server) == 1);
    REQUIRE(a.write(0, std::span(&move, 1)).ok());
}

TEST_CASE("a torque-off command to a map without a release says which parameters give one") {
    auto server = winch_driver();
    auto raw = winch_raw(server->port());
    raw.erase("deactivate_values");
    ModbusActuator a;
    REQUIRE(a.on_configure(validated(raw), {}).ok());
    REQUIRE(a.on_activate().ok());
    const JointCommand off = torque_off();
    auto st = a.write(0, std::span(&off, 1));
    CHECK(st.code() == ErrorCode::unsupported);
    CHECK(st.message().find("'deactivate_values'") != std::string::npos);
    CHECK(enable_register(*server) == 1);
}

TEST_CASE("recover writes the release to a device that answers, and reports one that does not") {
    auto server = winch_driver();
    ModbusActuator a;
    configure_and_activate(a, server->port());
    const JointCommand move = goal(20.0);
    REQUIRE(a.write(0, std::span(&move, 1)).ok());
    SECTION("answers: released, link closed") {
        testing::LogCapture log;
        REQUIRE(a.on_recover().ok());
        CHECK(enable_register(*server) == 0);
        CHECK(log.lines().empty());
        std::vector<JointState> s(1);
        CHECK_FALSE(a.read(0, s).ok());
    }
    SECTION("silent: recover still ends, with a warning naming the joint") {
        server->set_mute(true);
        testing::LogCapture log;
        REQUIRE(a.on_recover().ok());
        CHECK(log.count("joint 'winch': release on recover") == 1);
        CHECK(log.count("may still hold or drive its last goal") == 1);
        server->set_mute(false);
        CHECK(enable_register(*server) == 1);
    }
}

TEST_CASE("deactivate_values without an activation register is refused") {
    auto server = winch_driver();
    auto raw = winch_raw(server->port());
    raw.erase("activate_register");
    raw.erase("activate_values");
    ModbusActuator a;
    auto st = a.on_configure(validated(raw), {});
    CHECK(st.code() == ErrorCode::invalid_argument);
    CHECK(st.message().find("'deactivate_values' is set but 'activate_register' is not") != std::string::npos);
}

TEST_CASE("a fault register reading non-zero shows as the joint's fault") {
    auto server = winch_driver();
    ModbusActuator a;
    configure_and_activate(a, server->port());
    server->with_registers([](auto& h, auto&) { h[5] = 0x0B; return 0; });
    std::vector<JointState> s(1);
    REQUIRE(a.read(0, s).ok());
    CHECK(s[0].fault_bits == 0x0B);
    CHECK(s[0].fault == "device fault code 0xB");
    // A faulted device is not activated again until the fault is cleared.
    REQUIRE(a.on_deactivate().ok());
    auto st = a.on_activate();
    CHECK(st.code() == ErrorCode::hardware_fault);
    CHECK(st.message().find("'winch'") != std::string::npos);
}

TEST_CASE("a server that stops answering ends in a timeout naming the joint and the link") {
    auto server = winch_driver();
    ModbusActuator a;
    configure_and_activate(a, server->port());
    server->set_mute(true);
    std::vector<JointState> s(1);
    auto st = a.read(0, s);
    CHECK(st.code() == ErrorCode::timeout);
    CHECK(st.message().find("'winch'") != std::string::npos);
    CHECK(st.message().find("127.0.0.1:" + std::to_string(server->port())) != std::string::npos);
    CHECK(st.message().find("2 attempts") != std::string::npos);
    const JointCommand cmd = goal(30.0);
    CHECK(a.write(0, std::span(&cmd, 1)).code() == ErrorCode::timeout);
    // It answers again: so do we.
    server->set_mute(false);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    CHECK(a.read(0, s).ok());
}

TEST_CASE("a Robotiq 2F-85 style byte map: command block, activation handshake, byte-packed status") {
    // hardware.md §5: commands from 1000 (byte 0 action: bit0 rACT, bit3 rGTO;
    // byte 3 position; byte 4 speed; byte 5 force), status input registers
    // from 2000 (byte 0: gSTA bits 4-5, gOBJ bits 6-7; byte 2 fault; byte 4
    // position; byte 5 current). Two bytes per register, byte 0 high.
    ModbusLoopbackServer server(2100, [pos = 0.0, activated = 0.0](std::vector<std::uint16_t>& h,
                                                                    std::vector<std::uint16_t>& in, double dt) mutable {
        const int action = h[1000] >> 8;
        const bool act = action & 0x01, go = action & 0x08;
        activated = act ? activated + dt : 0.0;
        const bool ready = activated > 0.1;
        const double request = h[1001] & 0xFF;
        if (ready && go) {
            const double step = 360.0 * dt;
            pos = std::abs(request - pos) <= step ? request : pos + (request > pos ? step : -step);
        }
        const bool arrived = std::lround(pos) == std::lround(request);
        const int gsta = ready ? 3 : (act ? 1 : 0);
        const int gobj = (ready && go) ? (arrived ? 3 : 0) : 0;
        in[2000] = static_cast<std::uint16_t>(((gobj << 6) | (gsta << 4) | (go ? 0x08 : 0) | (act ? 1 : 0)) << 8);
        in[2001] = static_cast<std::uint16_t>(h[1001] & 0xFF);  // fault 0, position request echo
        in[2002] = static_cast<std::uint16_t>((std::lround(pos) << 8) | (arrived ? 0 : 25));
    });
    std::map<std::string, ParamValue> raw{
        {"port", std::int64_t{server.port()}},
        {"slave", std::int64_t{9}},
        {"name", std::string("gripper")},
        {"unit", std::string("mm")},
        {"min", 0.0},
        {"max", 85.0},
        {"goal_register", std::int64_t{1001}},
        {"goal_format", std::string("u8_low")},
        {"goal_scale", -85.0 / 255.0},
        {"goal_offset", 85.0},
        {"command_register", std::int64_t{1000}},
        {"command_template", std::vector<std::int64_t>{0x0900, 0x0000, 0xFFFF}},
        {"activate_register", std::int64_t{1000}},
        {"activate_values", std::vector<std::int64_t>{0x0100}},
        {"deactivate_values", std::vector<std::int64_t>{0x0000}},
        {"state_table", std::string("input")},
        {"position_register", std::int64_t{2002}},
        {"position_format", std::string("u8_high")},
        {"position_scale", -85.0 / 255.0},
        {"position_offset", 85.0},
        {"status_register", std::int64_t{2000}},
        {"status_format", std::string("u8_high")},
        {"moving_mask", std::int64_t{0xC8}},  // gGTO set and gOBJ = 0: moving toward the request
        {"moving_value", std::int64_t{0x08}},
        {"ready_mask", std::int64_t{0x30}},
        {"ready_value", std::int64_t{0x30}},
        {"fault_register", std::int64_t{2001}},
        {"fault_format", std::string("u8_high")},
        {"current_register", std::int64_t{2002}},
        {"current_format", std::string("u8_low")},
        {"current_scale", 10.0},
    };
    ModbusActuator a;
    REQUIRE(a.on_configure(validated(raw), {}).ok());
    auto st = a.on_activate();
    INFO(st.message());
    REQUIRE(st.ok());
    // Activation handshake done, then the command block holds the present opening (85 mm = count 0).
    CHECK(server.with_registers([](auto& h, auto&) { return std::vector<int>{h[1000], h[1001], h[1002]}; }) ==
          std::vector<int>{0x0900, 0x0000, 0xFFFF});
    const JointCommand close_to_40 = goal(40.0);
    REQUIRE(a.write(0, std::span(&close_to_40, 1)).ok());
    const int request = server.with_registers([](auto& h, auto&) { return h[1001] & 0xFF; });
    CHECK(request == std::lround((85.0 - 40.0) * 255.0 / 85.0));
    std::vector<JointState> s(1);
    for (int i = 0; i < 100; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        REQUIRE(a.read(0, s).ok());
        if (!s[0].moving && std::abs(s[0].position - 40.0) < 0.5) break;
    }
    CHECK_FALSE(s[0].moving);
    CHECK(s[0].position == Approx(40.0).margin(0.2));
    CHECK(s[0].fault.empty());
    // The safe state's torque off: rACT and rGTO cleared, the go-to is not executed any more.
    const JointCommand off = torque_off();
    REQUIRE(a.write(0, std::span(&off, 1)).ok());
    CHECK(server.with_registers([](auto& h, auto&) { return int(h[1000]); }) == 0x0000);
}

TEST_CASE("register-map mistakes are explained") {
    auto server = winch_driver();
    SECTION("goal outside the command block") {
        auto raw = winch_raw(server->port());
        raw["command_register"] = std::int64_t{8};
        raw["command_template"] = std::vector<std::int64_t>{0, 0};
        ModbusActuator a;
        auto st = a.on_configure(validated(raw), {});
        CHECK(st.code() == ErrorCode::invalid_argument);
        CHECK(st.message().find("outside the command block") != std::string::npos);
    }
    SECTION("a register the device does not have") {
        auto raw = winch_raw(server->port());
        raw["position_register"] = std::int64_t{400};
        raw["status_register"] = std::int64_t{-1};
        raw["fault_register"] = std::int64_t{-1};
        raw["current_register"] = std::int64_t{-1};
        raw["moving_mask"] = std::int64_t{0};
        raw["ready_mask"] = std::int64_t{0};
        ModbusActuator a;
        auto st = a.on_configure(validated(raw), {});
        CHECK(st.code() == ErrorCode::invalid_argument);
        CHECK(st.message().find("no such register") != std::string::npos);
    }
    SECTION("nobody listening") {
        auto raw = winch_raw(1);  // port 1: refused
        ModbusActuator a;
        auto st = a.on_configure(validated(raw), {});
        CHECK(st.code() == ErrorCode::io_error);
        CHECK(st.message().find("cannot connect") != std::string::npos);
    }
}
