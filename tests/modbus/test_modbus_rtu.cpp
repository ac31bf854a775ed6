// The `modbus` plugin over RTU: a libmodbus RTU server on one pseudo-terminal,
// the plugin on another, and a thread copying bytes between the two masters
// (a null-modem cable made of ptys). Same register map as the TCP winch driver.
#include <catch2/catch.hpp>

#include <modbus/modbus.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "modbus_actuator.hpp"
#include "rollsense/hal/pty_pair.hpp"

using namespace rollsense;

namespace {

class NullModem {
public:
    NullModem() {
        auto a = hal::PtyPair::open();
        auto b = hal::PtyPair::open();
        REQUIRE(a.ok());
        REQUIRE(b.ok());
        a_ = std::move(a).value();
        b_ = std::move(b).value();
        thread_ = std::thread([this] { pump(); });
    }
    ~NullModem() {
        running_ = false;
        thread_.join();
    }
    const std::string& end_a() const { return a_.slave_path(); }
    const std::string& end_b() const { return b_.slave_path(); }

private:
    void pump() {
        std::uint8_t buf[512];
        while (running_) {
            pollfd p[2] = {{a_.master_fd(), POLLIN, 0}, {b_.master_fd(), POLLIN, 0}};
            if (::poll(p, 2, 5) <= 0) continue;
            for (int i = 0; i < 2; ++i) {
                if (!(p[i].revents & POLLIN)) continue;
                const ssize_t n = ::read(p[i].fd, buf, sizeof buf);
                if (n > 0) (void)!::write(p[1 - i].fd, buf, static_cast<std::size_t>(n));
            }
        }
    }
    hal::PtyPair a_, b_;
    std::atomic<bool> running_{true};
    std::thread thread_;
};

// A slave-9 RTU device with a goal (s32 at 0), position (s32 at 2) that jumps
// to the goal while register 10 (enable) is 1.
class RtuDevice {
public:
    explicit RtuDevice(const std::string& device) {
        ctx_ = modbus_new_rtu(device.c_str(), 115200, 'N', 8, 1);
        REQUIRE(ctx_);
        REQUIRE(modbus_set_slave(ctx_, 9) == 0);
        REQUIRE(modbus_connect(ctx_) == 0);
        map_ = modbus_mapping_new(0, 0, 16, 0);
        map_->tab_registers[3] = 500;  // 5.00 mm
        map_->tab_registers[1] = 7000; // stale goal 70 mm
        thread_ = std::thread([this] { serve(); });
    }
    ~RtuDevice() {
        running_ = false;
        thread_.join();
        modbus_mapping_free(map_);
        modbus_close(ctx_);
        modbus_free(ctx_);
    }
    std::uint16_t reg(int i) { std::lock_guard l(m_); return map_->tab_registers[i]; }

private:
    void serve() {
        std::uint8_t q[MODBUS_RTU_MAX_ADU_LENGTH];
        while (running_) {
            pollfd p{modbus_get_socket(ctx_), POLLIN, 0};
            if (::poll(&p, 1, 5) <= 0) continue;
            const int n = modbus_receive(ctx_, q);
            if (n <= 0) continue;
            std::lock_guard l(m_);
            modbus_reply(ctx_, q, n, map_);
            if (map_->tab_registers[10] == 1) {
                map_->tab_registers[2] = map_->tab_registers[0];
                map_->tab_registers[3] = map_->tab_registers[1];
            }
        }
    }
    modbus_t* ctx_ = nullptr;
    modbus_mapping_t* map_ = nullptr;
    std::mutex m_;
    std::atomic<bool> running_{true};
    std::thread thread_;
};

}  // namespace

TEST_CASE("the modbus plugin drives a register-mapped joint over RTU through a pty null-modem") {
    NullModem cable;
    RtuDevice device(cable.end_b());
    std::map<std::string, ParamValue> raw{
        {"transport", std::string("rtu")},
        {"device", cable.end_a()},
        {"baud", std::int64_t{115200}},
        {"slave", std::int64_t{9}},
        {"timeout_ms", std::int64_t{200}},
        {"name", std::string("winch")},
        {"min", -100.0},
        {"max", 200.0},
        {"goal_register", std::int64_t{0}},
        {"goal_scale", 0.01},
        {"position_register", std::int64_t{2}},
        {"position_scale", 0.01},
        {"activate_register", std::int64_t{10}},
        {"activate_values", std::vector<std::int64_t>{1}},
    };
    auto params = validate_params(modbus::modbus_schema(), raw, "test");
    REQUIRE(params.ok());
    modbus::ModbusActuator a;
    auto st = a.on_configure(*params, {});
    INFO(st.message());
    REQUIRE(st.ok());
    REQUIRE(a.on_activate().ok());
    CHECK(device.reg(1) == 500);  // the stale goal was replaced by the present position
    std::vector<JointState> s(1);
    REQUIRE(a.read(0, s).ok());
    CHECK(s[0].position == Approx(5.0));
    JointCommand c;
    c.position = 42.5;
    REQUIRE(a.write(0, std::span(&c, 1)).ok());
    REQUIRE(a.read(0, s).ok());
    CHECK(s[0].position == Approx(42.5));
}
