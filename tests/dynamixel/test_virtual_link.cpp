// What is particular to the in-memory VirtualBusLink (what etroll-virtual runs
// on): bytes handed over as they are written, replies queued at once, and
// timeouts on the link's own clock, so every time below is exact, whatever the
// load on the machine. The scenarios it shares with the pty (retries, CRC
// errors, silent servos, garbage, hardware errors, baud rates) run on both
// transports in test_bus.cpp.
#include <catch2/catch.hpp>

#include <array>

#include "rollsense/hal/dynamixel/bus.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/virtual_link.hpp"

using namespace rollsense;
using namespace rollsense::hal;
using namespace rollsense::hal::dxl;
using namespace std::chrono_literals;

namespace {

constexpr std::uint32_t kBaud = 57600;

std::unique_ptr<VirtualBusLink> etroll_link() {
    BusEmulator e;
    for (const auto& s : etroll_servos()) e.add_servo(s);  // 57600 baud, as from the factory
    return std::make_unique<VirtualBusLink>(std::move(e), kBaud);
}

struct Rig {
    VirtualBusLink* link = nullptr;  // owned by bus
    std::unique_ptr<Bus> bus;

    explicit Rig(BusOptions options = {100ms, 3}) {
        auto l = etroll_link();
        link = l.get();
        bus = std::make_unique<Bus>(std::move(l), options);
    }
};

Bytes read_everything(VirtualBusLink& link) {
    Bytes out;
    std::array<std::uint8_t, 64> buf{};
    while (auto n = link.read_some(buf, 0us).value()) out.insert(out.end(), buf.begin(), buf.begin() + n);
    return out;
}

}  // namespace

TEST_CASE("virtual link: a packet written in fragments is answered once its last byte is in") {
    auto link = etroll_link();
    const Bytes ping = build_instruction(2, Instruction::ping, {});
    for (std::size_t i = 0; i + 1 < ping.size(); ++i) {
        REQUIRE(link->write_all(std::span(ping).subspan(i, 1)).ok());
        CHECK(link->pending_bytes() == 0);
    }
    REQUIRE(link->write_all(std::span(ping).last(1)).ok());
    // The reply, read back three bytes at a time, is one whole status packet.
    Bytes reply;
    std::array<std::uint8_t, 3> small{};
    while (link->pending_bytes() > 0) {
        auto n = link->read_some(small, 0us);
        REQUIRE(n.ok());
        REQUIRE(*n > 0);
        reply.insert(reply.end(), small.begin(), small.begin() + *n);
    }
    PacketParser parser;
    parser.feed(reply);
    auto p = parser.next();
    REQUIRE(p);
    REQUIRE(p->event == PacketParser::Event::packet);
    CHECK(p->packet.is_status());
    CHECK(p->packet.id == 2);
    CHECK(get_le(p->packet.params.data(), 2) == 1020);
    CHECK_FALSE(parser.next());
    CHECK(link->now() == SerialLink::Clock::time_point{});  // nothing waited
}

TEST_CASE("virtual link: a SYNC_READ's status packets all come back in one read") {
    auto link = etroll_link();
    Bytes params;
    put_u16(params, kStateBlockAddress);
    put_u16(params, kStateBlockLength);
    for (std::uint8_t id : {1, 2, 3, 4}) params.push_back(id);
    REQUIRE(link->write_all(build_instruction(kBroadcastId, Instruction::sync_read, params)).ok());
    std::array<std::uint8_t, 512> buf{};
    auto n = link->read_some(buf, 30ms);
    REQUIRE(n.ok());
    CHECK(*n == 4 * (11 + kStateBlockLength));  // header 7 + instruction + error + CRC 2, per servo
    CHECK(link->pending_bytes() == 0);
}

TEST_CASE("virtual link: stuffed bytes reach the control table intact") {
    Rig rig;
    // -131073 is FF FF FD FF little-endian: a header inside the parameters of
    // the WRITE and of the status packet, stuffed by each sender. The winch is
    // in extended position mode, where that goal is in range.
    REQUIRE(rig.bus->write_value(4, addr::goal_position, 4, -131073).ok());
    auto v = rig.bus->read_value(4, addr::goal_position, 4);
    REQUIRE(v.ok());
    CHECK(*v == -131073);
}

TEST_CASE("virtual link: an instruction with a corrupt CRC gets the servo's CRC error status") {
    auto link = etroll_link();
    Bytes bad = build_instruction(1, Instruction::ping, {});
    bad.back() ^= 0xFF;
    REQUIRE(link->write_all(bad).ok());
    PacketParser parser;
    parser.feed(read_everything(*link));
    auto p = parser.next();
    REQUIRE(p);
    REQUIRE(p->event == PacketParser::Event::packet);
    CHECK(p->packet.error_code() == static_cast<std::uint8_t>(dxl::StatusError::crc));
    CHECK(link->bus().crc_errors_seen() == 1);
}

TEST_CASE("virtual link: a silent servo times out on the link's clock, exactly, after the bounded retries") {
    Rig rig;
    rig.link->bus().set_faults(3, {-1, 0});
    const auto before = rig.link->now();
    REQUIRE(rig.bus->read_value(3, addr::present_position, 4).error().code == ErrorCode::timeout);
    // Four reply timeouts and three pauses of 20 byte times before the retries.
    const auto byte = std::chrono::nanoseconds(10'000'000'000LL / kBaud);
    CHECK(rig.link->now() - before == 4 * std::chrono::nanoseconds(100ms) + 3 * 20 * byte);
    CHECK(rig.bus->port().fd() == -1);  // no descriptor: nothing for a crash handler to write to
    // The others still answer, at once.
    const auto after = rig.link->now();
    CHECK(rig.bus->ping(1).ok());
    CHECK(rig.link->now() == after);
}

TEST_CASE("virtual link: a slow servo's reply arrives late on the link's clock") {
    SECTION("later than the reply timeout: a timeout, and the late replies are not taken for later answers") {
        Rig rig;
        rig.link->bus().set_faults(2, {0, 0, kLateBy});
        auto v = rig.bus->read_value(2, addr::model_number, 2);
        REQUIRE_FALSE(v.ok());
        CHECK(v.error().code == ErrorCode::timeout);
        CHECK(rig.link->pending_bytes() > 0);  // still on their way
        rig.link->bus().set_faults(2, {});
        rig.link->pause(kLateBy);              // they have landed now
        auto w = rig.bus->read_value(2, addr::profile_velocity, 4);  // starts by dropping stale input
        REQUIRE(w.ok());
        CHECK(*w == 0);
    }
    SECTION("within the reply timeout: answered, and exactly that much time has passed") {
        Rig rig(BusOptions{1000ms, 0});
        rig.link->bus().set_faults(2, {0, 0, kLateBy});
        const auto before = rig.link->now();
        auto v = rig.bus->read_value(2, addr::model_number, 2);
        REQUIRE(v.ok());
        CHECK(*v == 1020);
        CHECK(rig.link->now() - before == std::chrono::nanoseconds(kLateBy));
    }
}

TEST_CASE("virtual link: scheduled faults start on the servos' time line") {
    Rig rig;
    rig.link->bus().schedule(InjectedFault{1, FaultKind::silent, 2.0});
    rig.link->advance_servos_to(0.0);
    rig.link->advance_servos_to(1.9);
    CHECK(rig.bus->ping(1).ok());
    rig.link->advance_servos_to(2.0);
    auto p = rig.bus->ping(1);
    REQUIRE_FALSE(p.ok());
    CHECK(p.error().code == ErrorCode::timeout);
    rig.link->advance_servos_to(1.0);  // time never runs backwards
    CHECK(rig.link->bus().elapsed() == Approx(2.0));
}
