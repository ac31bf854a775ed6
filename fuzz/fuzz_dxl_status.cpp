// Dynamixel Protocol 2.0 status packets (hal/dynamixel/src/protocol.cpp): the
// input is split into the chunks a serial port might deliver (chunk sizes
// from the input itself) and fed to the streaming parser; every packet it
// returns is described as the bus would, and must build back to a packet the
// parser reads identically.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_support.hpp"
#include "rollsense/hal/dynamixel/bus.hpp"
#include "rollsense/hal/dynamixel/protocol.hpp"

namespace dxl = rollsense::hal::dxl;

namespace {
void check_round_trip(const dxl::Packet& p) {
    if (!p.is_status()) return;
    const auto bytes = dxl::build_status(p.id, p.error, p.params);
    dxl::PacketParser again;
    again.feed(bytes);
    auto out = again.next();
    if (!out || out->event != dxl::PacketParser::Event::packet || out->packet.params != p.params ||
        out->packet.error != p.error || out->packet.id != p.id)
        rollsense::fuzz::invariant_broken("a status packet does not survive build_status -> parse");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::size_t chunk = 1 + data[0] % 64;
    dxl::PacketParser parser;
    for (std::size_t at = 1; at < size; at += chunk) {
        parser.feed(std::span<const std::uint8_t>(data + at, std::min(chunk, size - at)));
        while (auto out = parser.next()) {
            if (out->event != dxl::PacketParser::Event::packet) continue;
            const auto& p = out->packet;
            if (p.params.size() > dxl::kMaxPacketLength) rollsense::fuzz::invariant_broken("oversized params");
            (void)dxl::describe_status_error(p.error);
            (void)dxl::status_packet_error(p.id, static_cast<dxl::Instruction>(p.instruction), p.error);
            if (p.params.size() >= 1) (void)dxl::describe_hardware_error(p.params[0]);
            if (p.params.size() >= 4) (void)dxl::get_le_signed(p.params.data(), 4);
            check_round_trip(p);
        }
        if (parser.buffered() > 2 * (dxl::kMaxPacketLength + 64))
            rollsense::fuzz::invariant_broken("the parser buffers more than one packet's worth");
    }
    return 0;
}
