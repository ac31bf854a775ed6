// The fake bus follows the wire: address ACK/NACK, repeated START, one STOP,
// wired-AND reads, virtual time, injected adapter errors — with the same
// typed errors the Linux backend returns.
#include <catch2/catch.hpp>

#include <cerrno>
#include <vector>

#include "rollsense/hal/fake_i2c_bus.hpp"

using namespace rollsense;
using namespace rollsense::hal;

namespace {

// A minimal register-file device: first written byte sets the pointer,
// further writes store, reads return and auto-increment.
class RegisterDevice final : public I2cDevice {
public:
    RegisterDevice(std::uint8_t address, std::uint8_t fill) : address_(address) { regs.fill(fill); }
    bool on_address(std::uint8_t a, bool, double) override {
        first_ = true;
        if (a == address_) ++addressed;
        return a == address_;
    }
    bool on_write_byte(std::uint8_t v, double) override {
        if (first_) pointer = v;
        else regs[pointer++ & 0x0f] = v;
        first_ = false;
        return v != 0xee;  // 0xEE is refused (data NACK)
    }
    std::uint8_t on_read_byte(double) override { return regs[pointer++ & 0x0f]; }
    void on_stop(double) override { ++stops; }

    std::array<std::uint8_t, 16> regs{};
    std::uint8_t pointer = 0;
    int stops = 0;
    int addressed = 0;

private:
    std::uint8_t address_;
    bool first_ = false;
};

std::shared_ptr<FakeI2cBus> fresh_bus(const std::string& name) {
    auto bus = FakeI2cBus::get(name);
    bus->reset();
    return bus;
}

}  // namespace

TEST_CASE("open_i2c_bus understands the three spec forms", "[i2c][fake]") {
    auto a = open_i2c_bus("fake:spec-test");
    REQUIRE(a.ok());
    CHECK(a.value() == std::static_pointer_cast<I2cBus>(FakeI2cBus::get("spec-test")));
    CHECK(a.value()->name() == "fake:spec-test");

    auto empty = open_i2c_bus("fake:");
    REQUIRE_FALSE(empty.ok());
    CHECK(empty.error().code == ErrorCode::invalid_argument);

    auto junk = open_i2c_bus("i2c1");
    REQUIRE_FALSE(junk.ok());
    CHECK(junk.error().code == ErrorCode::invalid_argument);
    CHECK_THAT(junk.error().message, Catch::Contains("/dev/i2c-N"));
}

TEST_CASE("a write-then-read is one transfer with a repeated START", "[i2c][fake]") {
    auto bus = fresh_bus("combined");
    auto dev = std::make_shared<RegisterDevice>(0x50, 0);
    for (int i = 0; i < 16; ++i) dev->regs[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(0x10 + i);
    bus->attach(dev);

    const std::uint8_t pointer[1] = {0x04};
    std::array<std::uint8_t, 3> out{};
    REQUIRE(bus->write_read(0x50, pointer, out).ok());
    CHECK(out == std::array<std::uint8_t, 3>{0x14, 0x15, 0x16});
    CHECK(dev->stops == 1);  // one STOP for the whole transfer

    auto log = bus->log();
    REQUIRE(log.size() == 2);
    CHECK(log[0].kind == I2cLogEntry::Kind::write);
    CHECK(log[0].data == std::vector<std::uint8_t>{0x04});
    CHECK_FALSE(log[0].repeated_start);
    CHECK(log[1].kind == I2cLogEntry::Kind::read);
    CHECK(log[1].repeated_start);
    CHECK(log[1].data == std::vector<std::uint8_t>{0x14, 0x15, 0x16});
    CHECK(log[1].time > log[0].time);
}

TEST_CASE("plain writes and reads reach the device", "[i2c][fake]") {
    auto bus = fresh_bus("plain");
    auto dev = std::make_shared<RegisterDevice>(0x20, 0);
    bus->attach(dev);
    const std::uint8_t data[3] = {0x02, 0xaa, 0xbb};
    REQUIRE(bus->write(0x20, data).ok());
    CHECK(dev->regs[2] == 0xaa);
    CHECK(dev->regs[3] == 0xbb);
    std::array<std::uint8_t, 2> out{};
    REQUIRE(bus->read(0x20, out).ok());  // pointer continues at 4
    CHECK(out == std::array<std::uint8_t, 2>{0x00, 0x00});
}

TEST_CASE("a NACK comes back as a typed error naming the bus and the address", "[i2c][fake]") {
    auto bus = fresh_bus("nack");
    auto dev = std::make_shared<RegisterDevice>(0x50, 0);
    bus->attach(dev);

    SECTION("nobody at the address") {
        std::array<std::uint8_t, 1> out{};
        auto s = bus->read(0x51, out);
        REQUIRE_FALSE(s.ok());
        CHECK(s.code() == ErrorCode::hardware_fault);
        CHECK_THAT(s.message(), Catch::Contains("fake:nack") && Catch::Contains("0x51") && Catch::Contains("NACK"));
        CHECK(dev->stops == 1);  // the master still sends STOP
    }
    SECTION("a refused data byte") {
        const std::uint8_t data[2] = {0x00, 0xee};
        auto s = bus->write(0x50, data);
        REQUIRE_FALSE(s.ok());
        CHECK(s.code() == ErrorCode::hardware_fault);
        CHECK_THAT(s.message(), Catch::Contains("0x50"));
    }
    SECTION("a quick command nobody acknowledges") {
        auto s = bus->quick_write(0x33);
        REQUIRE_FALSE(s.ok());
        CHECK(s.code() == ErrorCode::hardware_fault);
        CHECK_THAT(s.message(), Catch::Contains("quick write") && Catch::Contains("0x33"));
        REQUIRE(bus->quick_read(0x50).ok());
        auto log = bus->log();
        REQUIRE(log.size() == 2);
        CHECK(log[0].kind == I2cLogEntry::Kind::quick);
        CHECK_FALSE(log[0].acked);
        CHECK(log[1].read_bit);
        CHECK(log[1].acked);
    }
}

TEST_CASE("adapter errors (EIO, timeout, arbitration) are typed", "[i2c][fake]") {
    auto bus = fresh_bus("errno");
    bus->attach(std::make_shared<RegisterDevice>(0x50, 0));
    std::array<std::uint8_t, 1> out{};

    bus->inject_errno(ETIMEDOUT);
    auto t = bus->read(0x50, out);
    CHECK(t.code() == ErrorCode::timeout);
    CHECK_THAT(t.message(), Catch::Contains("fake:errno") && Catch::Contains("0x50") && Catch::Contains("pull-up"));

    bus->inject_errno(EIO);
    auto e = bus->quick_write(0x50);
    CHECK(e.code() == ErrorCode::io_error);
    CHECK_THAT(e.message(), Catch::Contains("I/O error"));

    bus->inject_errno(EAGAIN);
    CHECK(bus->read(0x50, out).code() == ErrorCode::io_error);

    // The injection is used up: the bus works again.
    CHECK(bus->read(0x50, out).ok());
}

TEST_CASE("several devices answering one read combine as wired-AND", "[i2c][fake]") {
    auto bus = fresh_bus("wired-and");
    bus->attach(std::make_shared<RegisterDevice>(0x60, 0xf0));
    bus->attach(std::make_shared<RegisterDevice>(0x60, 0x3c));
    std::array<std::uint8_t, 2> out{};
    REQUIRE(bus->read(0x60, out).ok());
    CHECK(out[0] == 0x30);
    CHECK(out[1] == 0x30);
}

TEST_CASE("the adapter's capabilities are enforced", "[i2c][fake]") {
    auto bus = fresh_bus("caps");
    bus->attach(std::make_shared<RegisterDevice>(0x50, 0));
    I2cFunctionality smbus_only;
    smbus_only.combined_transfers = false;
    smbus_only.smbus_quick = true;
    bus->set_functionality(smbus_only);
    std::array<std::uint8_t, 1> out{};
    auto s = bus->read(0x50, out);
    CHECK(s.code() == ErrorCode::unsupported);
    CHECK_THAT(s.message(), Catch::Contains("I2C_FUNC_I2C"));

    I2cFunctionality no_quick;
    no_quick.combined_transfers = true;
    no_quick.smbus_quick = false;
    bus->set_functionality(no_quick);
    auto q = bus->quick_write(0x50);
    CHECK(q.code() == ErrorCode::unsupported);
    CHECK_THAT(q.message(), Catch::Contains("I2C_FUNC_SMBUS_QUICK"));

    bus->set_functionality({true, true, 0});
    std::vector<std::array<std::uint8_t, 1>> bufs(43);
    std::vector<I2cMessage> msgs;
    for (auto& b : bufs) msgs.push_back({0x50, true, b});
    auto many = bus->transfer(msgs);
    CHECK(many.code() == ErrorCode::invalid_argument);
    CHECK_THAT(many.message(), Catch::Contains("42"));
}

TEST_CASE("virtual time: transfers take their bit time, sleep_for advances exactly", "[i2c][fake]") {
    auto bus = fresh_bus("clock");
    bus->attach(std::make_shared<RegisterDevice>(0x50, 0));
    bus->set_clock_hz(100e3);
    const double t0 = bus->now();
    REQUIRE(bus->quick_write(0x50).ok());
    // START + 9 address bits + STOP at 100 kHz = 11 bits = 110 µs
    CHECK(bus->now() - t0 == Approx(110e-6));
    const double t1 = bus->now();
    bus->sleep_for(std::chrono::microseconds(3000));
    CHECK(bus->now() - t1 == Approx(3e-3));
}
