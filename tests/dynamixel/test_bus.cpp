// The bus master against the emulator, over a real pseudo-terminal (what
// rollsense-dxl-emu and etroll-emulated use) and over the in-memory
// VirtualBusLink (what etroll-virtual uses): every scenario that does not
// depend on wall-clock pacing runs on both.
#include <catch2/catch.hpp>

#include "rollsense/hal/dynamixel/bus.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"
#include "rollsense/hal/dynamixel/virtual_link.hpp"

using namespace rollsense;
using namespace rollsense::hal;
using namespace rollsense::hal::dxl;
using namespace std::chrono_literals;

namespace {

BusEmulator etroll_bus() {
    BusEmulator e;
    for (const auto& s : etroll_servos()) e.add_servo(s);  // 57600 baud, as from the factory
    return e;
}

struct PtyRig {
    std::unique_ptr<PtyBusEmulator> emu;
    std::unique_ptr<Bus> bus;

    explicit PtyRig(PtyEmulatorOptions options = {false, 0}, BusOptions bus_options = {100ms, 3}) {
        auto started = PtyBusEmulator::start(etroll_bus(), options);
        REQUIRE(started.ok());
        emu = std::move(started).value();
        auto port = SerialPort::open(emu->device(), 57600);
        REQUIRE(port.ok());
        bus = std::make_unique<Bus>(std::move(port).value(), bus_options);
    }
    template <class F>
    auto with_bus(F f) {
        return emu->with_bus(f);
    }
};

struct VirtualRig {
    VirtualBusLink* link = nullptr;  // owned by bus
    std::unique_ptr<Bus> bus;

    VirtualRig() {
        auto l = std::make_unique<VirtualBusLink>(etroll_bus(), 57600);
        link = l.get();
        bus = std::make_unique<Bus>(std::move(l), BusOptions{100ms, 3});
    }
    template <class F>
    auto with_bus(F f) {
        return f(link->bus());
    }
};

}  // namespace

TEMPLATE_TEST_CASE("ping and scan find the E-TRoll servos with their model numbers", "", PtyRig, VirtualRig) {
    TestType rig;
    auto p = rig.bus->ping(3);
    REQUIRE(p.ok());
    CHECK(p->model_number == 1020);
    auto found = rig.bus->scan(0, 10, 5ms);
    REQUIRE(found.ok());
    REQUIRE(found->size() == 4);
    CHECK((*found)[3].id == 4);
    CHECK((*found)[3].model_number == 1200);
}

TEMPLATE_TEST_CASE("read and write single items", "", PtyRig, VirtualRig) {
    TestType rig;
    REQUIRE(rig.bus->write_value(2, addr::profile_velocity, 4, 15).ok());
    auto v = rig.bus->read_value(2, addr::profile_velocity, 4);
    REQUIRE(v.ok());
    CHECK(*v == 15);
    auto mode = rig.bus->read_value(4, addr::operating_mode, 1);
    REQUIRE(mode.ok());
    CHECK(*mode == 4);
}

TEMPLATE_TEST_CASE("one sync write moves every servo and one sync read returns every state", "", PtyRig, VirtualRig) {
    TestType rig;
    const std::uint8_t ids[] = {1, 2, 3, 4};
    for (auto id : ids) REQUIRE(rig.bus->write_value(id, addr::torque_enable, 1, 1).ok());
    std::vector<SyncWriteEntry> entries;
    for (auto id : ids) {
        Bytes d;
        put_le(d, 4096 / 8 * id, 4);  // 45 deg per id above 0 tick... absolute ticks
        entries.push_back({id, d});
    }
    const auto writes_before = rig.with_bus([](BusEmulator& b) { return b.sync_writes(); });
    REQUIRE(rig.bus->sync_write(addr::goal_position, 4, entries).ok());
    // SYNC_WRITE has no reply; a PING behind it proves the emulator has handled it.
    REQUIRE(rig.bus->ping(1).ok());
    // The emulator's clock is manual here: let 5 s pass.
    rig.with_bus([](BusEmulator& b) { b.advance(5.0); return 0; });
    auto states = rig.bus->sync_read(ids, kStateBlockAddress, kStateBlockLength);
    REQUIRE(states.ok());
    REQUIRE(states->size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK((*states)[i].id == ids[i]);
        const auto pos = get_le_signed(&(*states)[i].data[addr::present_position - kStateBlockAddress], 4);
        CHECK(pos == 512 * ids[i]);
        CHECK((*states)[i].data[0] == 0);  // not moving
    }
    CHECK(rig.with_bus([](BusEmulator& b) { return b.sync_writes(); }) == writes_before + 1);
    CHECK(rig.with_bus([](BusEmulator& b) { return b.sync_reads(); }) == 1);
}

TEMPLATE_TEST_CASE("status-packet errors become typed errors naming the servo", "", PtyRig, VirtualRig) {
    TestType rig;
    SECTION("a goal outside the position limits is a limit violation") {
        REQUIRE(rig.bus->write_value(1, addr::max_position_limit, 4, 3000).ok());
        auto st = rig.bus->write_value(1, addr::goal_position, 4, 3500);
        CHECK(st.code() == ErrorCode::limit_violation);
        CHECK(st.message().find("servo 1") != std::string::npos);
        CHECK(st.message().find("data limit") != std::string::npos);
    }
    SECTION("an EEPROM write with torque on is an access error (state error)") {
        REQUIRE(rig.bus->write_value(2, addr::torque_enable, 1, 1).ok());
        auto st = rig.bus->write_value(2, addr::operating_mode, 1, 0);
        CHECK(st.code() == ErrorCode::state_error);
        CHECK(st.message().find("servo 2") != std::string::npos);
        CHECK(st.message().find("access") != std::string::npos);
    }
    SECTION("an invalid operating mode is a data range error") {
        auto st = rig.bus->write_value(3, addr::operating_mode, 1, 2);
        CHECK(st.code() == ErrorCode::limit_violation);
        CHECK(st.message().find("data range") != std::string::npos);
    }
    SECTION("an unsupported instruction is a protocol error") {
        auto st = rig.bus->read(3, 200, 4);
        CHECK(st.error().code == ErrorCode::limit_violation);
    }
}

TEMPLATE_TEST_CASE("a dropped reply is retried and the transaction succeeds", "", PtyRig, VirtualRig) {
    TestType rig;
    rig.with_bus([](BusEmulator& b) { b.set_faults(2, {1, 0}); return 0; });
    auto v = rig.bus->read_value(2, addr::model_number, 2);
    REQUIRE(v.ok());
    CHECK(*v == 1020);
    CHECK(rig.bus->statistics().retries == 1);
    CHECK(rig.bus->statistics().timeouts == 1);
}

TEMPLATE_TEST_CASE("a servo that never answers ends in a timeout error after the bounded retries", "", PtyRig, VirtualRig) {
    TestType rig;
    rig.with_bus([](BusEmulator& b) { b.set_faults(3, {-1, 0}); return 0; });
    auto v = rig.bus->read_value(3, addr::present_position, 4);
    REQUIRE_FALSE(v.ok());
    CHECK(v.error().code == ErrorCode::timeout);
    CHECK(v.error().message.find("servo 3") != std::string::npos);
    CHECK(v.error().message.find("4 attempts") != std::string::npos);
    CHECK(rig.bus->statistics().timeouts == 4);
    CHECK(rig.bus->statistics().retries == 3);
    // The others still answer.
    CHECK(rig.bus->ping(1).ok());
}

TEMPLATE_TEST_CASE("a corrupted reply is retried, a servo that always corrupts ends in a CRC error", "", PtyRig, VirtualRig) {
    TestType rig;
    rig.with_bus([](BusEmulator& b) { b.set_faults(1, {0, 2}); return 0; });
    REQUIRE(rig.bus->ping(1).ok());
    CHECK(rig.bus->statistics().crc_errors == 2);
    CHECK(rig.bus->statistics().retries == 2);

    rig.with_bus([](BusEmulator& b) { b.set_faults(1, {0, -1}); return 0; });
    auto p = rig.bus->ping(1);
    REQUIRE_FALSE(p.ok());
    CHECK(p.error().code == ErrorCode::protocol_error);
    CHECK(p.error().message.find("CRC") != std::string::npos);
    CHECK(p.error().message.find("servo 1") != std::string::npos);
}

TEMPLATE_TEST_CASE("a sync read with one silent servo names that servo", "", PtyRig, VirtualRig) {
    TestType rig;
    rig.with_bus([](BusEmulator& b) { b.set_faults(3, {-1, 0}); return 0; });
    const std::uint8_t ids[] = {1, 2, 3, 4};
    auto r = rig.bus->sync_read(ids, kStateBlockAddress, kStateBlockLength);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::timeout);
    CHECK(r.error().message.find("servo 3") != std::string::npos);
    CHECK(r.error().message.find("SYNC_READ") != std::string::npos);
}

TEMPLATE_TEST_CASE("garbage on the line before a reply is skipped", "", PtyRig, VirtualRig) {
    TestType rig;
    rig.with_bus([](BusEmulator& b) {
        b.inject_garbage({0x00, 0xFF, 0xFF, 0xFD, 0x13, 0x37, 0xFF, 0xFF});
        return 0;
    });
    auto v = rig.bus->read_value(1, addr::model_number, 2);
    REQUIRE(v.ok());
    CHECK(*v == 1020);
    CHECK(rig.bus->statistics().retries == 0);
    CHECK(rig.bus->statistics().garbage_bytes > 0);
}

TEMPLATE_TEST_CASE("an injected hardware error shows as the alert bit, reboot clears it", "", PtyRig, VirtualRig) {
    TestType rig;
    rig.with_bus([](BusEmulator& b) { b.raise_hardware_error(2, hw_error::overheating); return 0; });
    auto r = rig.bus->read(2, addr::hardware_error_status, 1);
    REQUIRE(r.ok());
    CHECK(r->alert);
    CHECK(r->data[0] == hw_error::overheating);
    REQUIRE(rig.bus->reboot(2).ok());
    r = rig.bus->read(2, addr::hardware_error_status, 1);
    REQUIRE(r.ok());
    CHECK_FALSE(r->alert);
    CHECK(r->data[0] == 0);
}

TEST_CASE("with wire pacing a 4-servo control period costs about what the wire would") {
    // Not a timing threshold on the host: the paced emulator holds replies for
    // the computed wire time, so the lower bound is the physics, not the machine.
    PtyRig rig({false, 57600}, {100ms, 0});
    const std::uint8_t ids[] = {1, 2, 3, 4};
    const auto t0 = std::chrono::steady_clock::now();
    auto r = rig.bus->sync_read(ids, kStateBlockAddress, kStateBlockLength);
    const auto took = std::chrono::steady_clock::now() - t0;
    REQUIRE(r.ok());
    // SYNC_READ (18 bytes) + 4 x (25 bytes + 500 us return delay) at 57600 baud >= 22.5 ms.
    CHECK(took >= std::chrono::microseconds((18 + 4 * 25) * 10 * 1000000LL / 57600 + 4 * 500));
}

TEMPLATE_TEST_CASE("a servo only answers at its own baud rate, as on a real bus", "", PtyRig, VirtualRig) {
    TestType rig;
    // Move servo 2 to 1 Mbps (EEPROM, torque is off): it answers that write at the old rate.
    REQUIRE(rig.bus->write_value(2, addr::baud_rate, 1, *index_from_baud(1000000)).ok());
    auto lost = rig.bus->ping(2);
    REQUIRE_FALSE(lost.ok());
    CHECK(lost.error().code == ErrorCode::timeout);
    CHECK(rig.bus->ping(1).ok());
    REQUIRE(rig.bus->port().set_baud(1000000).ok());
    auto p = rig.bus->ping(2);
    REQUIRE(p.ok());
    CHECK(p->model_number == 1020);
    CHECK_FALSE(rig.bus->ping(1).ok());  // and now the others are the ones out of step
}

TEST_CASE("a sync read cut short by a CRC fault: the next READ takes its own reply, not a late one") {
    // Paced like a wire: when servo 1's corrupt reply ends the SYNC_READ, the
    // replies of servos 2-4 are still on their way; servo 2's (14 bytes) reaches
    // the line after the next transaction's flush, ahead of its answer to the READ.
    PtyRig rig({false, 57600}, {100ms, 0});
    rig.with_bus([](BusEmulator& b) { b.set_faults(1, {0, -1}); return 0; });
    const std::uint8_t ids[] = {1, 2, 3, 4};
    auto r = rig.bus->sync_read(ids, kStateBlockAddress, kStateBlockLength);
    REQUIRE_FALSE(r.ok());
    REQUIRE(r.error().code == ErrorCode::protocol_error);
    const std::uint16_t block = addr::torque_enable - addr::operating_mode + 1;  // the plugin's prepare() read
    auto read = rig.bus->read(2, addr::operating_mode, block);
    INFO((read.ok() ? std::string() : read.error().message));
    REQUIRE(read.ok());
    CHECK(read->data.size() == block);
    CHECK(read->data[0] == static_cast<std::uint8_t>(OperatingMode::position));   // 11 Operating Mode
    CHECK(read->data[block - 1] == 0);                                             // 64 Torque Enable: off
    CHECK(rig.bus->statistics().stale_replies == 1);
}

// Review of the change: a reply of another length was skipped in silence, so a
// servo that answered was reported as one that did not ("check its power, its id").
TEST_CASE("a servo whose only reply has another length is named as answering, with both lengths") {
    PtyRig rig({false, 57600}, {100ms, 0});  // no retries: the one attempt sees the late reply
    rig.with_bus([](BusEmulator& b) { b.set_faults(1, {0, -1}); return 0; });
    const std::uint8_t ids[] = {1, 2, 3, 4};
    REQUIRE_FALSE(rig.bus->sync_read(ids, kStateBlockAddress, kStateBlockLength).ok());
    rig.with_bus([](BusEmulator& b) { b.set_faults(2, {-1, 0}); return 0; });  // its own answer never comes
    auto read = rig.bus->read(2, addr::operating_mode, 54);
    REQUIRE_FALSE(read.ok());
    INFO(read.error().message);
    CHECK(read.error().code == ErrorCode::protocol_error);
    CHECK_THAT(read.error().message, Catch::Contains("servo 2 answered READ with " + std::to_string(kStateBlockLength) +
                                                     " bytes of data, not the 54 asked for"));
}

// Scan stops only when the port fails (below): one servo's bad reply is that id's.
TEMPLATE_TEST_CASE("scan goes past a servo whose replies are garbled", "", PtyRig, VirtualRig) {
    TestType rig;
    rig.with_bus([](BusEmulator& b) { b.set_faults(2, {0, -1}); return 0; });  // every reply of servo 2 garbled
    auto found = rig.bus->scan(1, 4, 20ms);
    REQUIRE(found.ok());
    std::vector<int> ids;
    for (const auto& p : *found) ids.push_back(p.id);
    CHECK(ids == std::vector<int>{1, 3, 4});
}

TEST_CASE("a port lost mid-run (adapter pulled, emulator gone) is a device failure, not a file error") {
    PtyRig rig;
    REQUIRE(rig.bus->ping(1).ok());
    rig.emu.reset();  // the other end of the line is gone
    auto p = rig.bus->ping(1);
    REQUIRE_FALSE(p.ok());
    INFO(p.error().message);
    CHECK(p.error().code == ErrorCode::hardware_fault);  // exit 4 ("a device failed or stopped answering"), not 5
    CHECK(rig.bus->statistics().retries == 0);            // no retries into a dead port
    auto w = rig.bus->write_value(1, addr::led, 1, 1);
    REQUIRE_FALSE(w.ok());
    CHECK(w.code() == ErrorCode::hardware_fault);
    auto scan = rig.bus->scan(1, 4, 20ms);  // stops at the first id: the port, not a servo, failed
    REQUIRE_FALSE(scan.ok());
    CHECK(scan.error().code == ErrorCode::hardware_fault);
}
