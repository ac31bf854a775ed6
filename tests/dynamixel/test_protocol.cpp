// Protocol 2.0 codec: CRC, stuffing, packet building and parsing, resync.
#include <catch2/catch.hpp>

#include <string>

#include "rollsense/hal/dynamixel/protocol.hpp"

using namespace rollsense::hal::dxl;

namespace {
Bytes bytes_of(const std::string& s) { return Bytes(s.begin(), s.end()); }
std::vector<PacketParser::Output> parse_all(PacketParser& p) {
    std::vector<PacketParser::Output> out;
    while (auto o = p.next()) out.push_back(std::move(*o));
    return out;
}
}  // namespace

TEST_CASE("CRC-16 matches the CRC-16/BUYPASS check value") {
    CHECK(crc16(bytes_of("123456789")) == 0xFEE8);
    CHECK(crc16(Bytes{}) == 0x0000);
}

TEST_CASE("CRC-16 of the manual's PING example") {
    // PING to id 1: FF FF FD 00 01 03 00 01, CRC 0x4E19 sent as 19 4E.
    const Bytes ping = build_instruction(1, Instruction::ping, {});
    CHECK(ping == Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E});
}

TEST_CASE("the manual's READ example builds byte for byte") {
    // READ id 1, address 132 (Present Position), 4 bytes.
    const Bytes params{0x84, 0x00, 0x04, 0x00};
    CHECK(build_instruction(1, Instruction::read, params) ==
          Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x02, 0x84, 0x00, 0x04, 0x00, 0x1D, 0x15});
}

TEST_CASE("stuffing inserts FD after every FF FF FD and unstuffing removes it") {
    CHECK(stuff(Bytes{0x03, 0xFF, 0xFF, 0xFD, 0x01}) == Bytes{0x03, 0xFF, 0xFF, 0xFD, 0xFD, 0x01});
    CHECK(stuff(Bytes{0xFF, 0xFF, 0xFD}) == Bytes{0xFF, 0xFF, 0xFD, 0xFD});
    CHECK(stuff(Bytes{0xFF, 0xFD, 0xFF}) == Bytes{0xFF, 0xFD, 0xFF});  // not a header: untouched

    const std::vector<Bytes> cases{
        {},
        {0x01, 0x02, 0x03},
        {0xFF, 0xFF, 0xFD},
        {0xFF, 0xFF, 0xFD, 0xFD},
        {0xFF, 0xFF, 0xFD, 0xFF, 0xFF, 0xFD, 0x00},
        {0xFF, 0xFF, 0xFF, 0xFD, 0xFD, 0xFD},
        {0x55, 0x00, 0xFF, 0xFF, 0xFD, 0x00, 0xFF, 0xFF, 0xFD},
    };
    for (const auto& c : cases) {
        INFO("payload size " << c.size());
        const Bytes s = stuff(c);
        CHECK(unstuff(s) == c);
        // A stuffed payload never contains a header (FF FF FD not followed by FD).
        for (std::size_t i = 0; i + 3 < s.size(); ++i)
            if (s[i] == 0xFF && s[i + 1] == 0xFF && s[i + 2] == 0xFD) CHECK(s[i + 3] == 0xFD);
    }
}

TEST_CASE("stuffing round trip over every 4-byte window of FF/FD/00 values") {
    const std::uint8_t alphabet[] = {0xFF, 0xFD, 0x00};
    for (int a = 0; a < 81; ++a) {
        Bytes payload;
        for (int k = 0, v = a; k < 4; ++k, v /= 3) payload.push_back(alphabet[v % 3]);
        payload.insert(payload.begin(), payload.begin(), payload.end());  // 8 bytes, more overlaps
        REQUIRE(unstuff(stuff(payload)) == payload);
    }
}

TEST_CASE("a packet whose parameters contain the header is stuffed on the wire and parsed back") {
    const Bytes params{0x74, 0x00, 0xFF, 0xFF, 0xFD, 0x00, 0xFF, 0xFF, 0xFD};
    const Bytes wire = build_instruction(3, Instruction::write, params);
    // LEN counts the two stuffing bytes: INST + 9 params + 2 stuffed + CRC.
    CHECK(get_le(&wire[5], 2) == 1 + 9 + 2 + 2);
    PacketParser p;
    p.feed(wire);
    auto out = parse_all(p);
    REQUIRE(out.size() == 1);
    REQUIRE(out[0].event == PacketParser::Event::packet);
    CHECK(out[0].packet.id == 3);
    CHECK(out[0].packet.instruction == static_cast<std::uint8_t>(Instruction::write));
    CHECK(out[0].packet.params == params);
}

TEST_CASE("status packets parse into id, error byte and parameters") {
    const Bytes params{0x00, 0x08, 0x00, 0x00};
    PacketParser p;
    p.feed(build_status(7, 0x80 | 4, params));
    auto out = parse_all(p);
    REQUIRE(out.size() == 1);
    const auto& pk = out[0].packet;
    CHECK(pk.is_status());
    CHECK(pk.id == 7);
    CHECK(pk.alert());
    CHECK(pk.error_code() == 4);
    CHECK(pk.params == params);
}

TEST_CASE("every status-packet error code has its own meaning") {
    CHECK(describe_status_error(0).empty());
    std::vector<std::string> seen;
    for (std::uint8_t code = 1; code <= 7; ++code) {
        PacketParser p;
        p.feed(build_status(1, code, {}));
        auto out = parse_all(p);
        REQUIRE(out.size() == 1);
        CHECK(out[0].packet.error_code() == code);
        const auto text = describe_status_error(out[0].packet.error);
        CHECK_FALSE(text.empty());
        for (const auto& s : seen) CHECK(s != text);
        seen.push_back(text);
    }
    CHECK(describe_status_error(1).find("result fail") != std::string::npos);
    CHECK(describe_status_error(2).find("instruction") != std::string::npos);
    CHECK(describe_status_error(3).find("CRC") != std::string::npos);
    CHECK(describe_status_error(4).find("range") != std::string::npos);
    CHECK(describe_status_error(5).find("length") != std::string::npos);
    CHECK(describe_status_error(6).find("limit") != std::string::npos);
    CHECK(describe_status_error(7).find("access") != std::string::npos);
    CHECK(describe_status_error(0x80).find("hardware alert") != std::string::npos);
}

TEST_CASE("hardware error bits are spelled out") {
    CHECK(describe_hardware_error(0) == "");
    CHECK(describe_hardware_error(hw_error::overload) == "overload");
    CHECK(describe_hardware_error(hw_error::overheating | hw_error::input_voltage) ==
          "input voltage out of range, overheating");
    CHECK(describe_hardware_error(0x40).find("unknown bits 0x40") != std::string::npos);
}

TEST_CASE("the parser resynchronises after garbage, including header-like garbage") {
    const Bytes a = build_status(1, 0, Bytes{0x10, 0x20});
    const Bytes b = build_status(2, 0, Bytes{0x30});
    Bytes stream{0x00, 0x13, 0xFF, 0xFF, 0xFF, 0xFD, 0x42};  // noise with a partial header
    stream.insert(stream.end(), a.begin(), a.end());
    stream.insert(stream.end(), {0xFF, 0xFF, 0xFD, 0x00, 0x09, 0xFF, 0xFF});  // a header with an absurd length
    stream.insert(stream.end(), b.begin(), b.end());
    PacketParser p;
    p.feed(stream);
    std::vector<int> ids;
    for (const auto& o : parse_all(p))
        if (o.event == PacketParser::Event::packet) ids.push_back(o.packet.id);
    CHECK(ids == std::vector<int>{1, 2});
    CHECK(p.discarded() > 0);
}

TEST_CASE("a packet split into single bytes is reassembled") {
    const Bytes a = build_status(9, 0, Bytes{1, 2, 3, 0xFF, 0xFF, 0xFD});
    PacketParser p;
    int packets = 0;
    for (auto byte : a) {
        p.feed(Bytes{byte});
        while (auto o = p.next()) packets += o->event == PacketParser::Event::packet;
    }
    CHECK(packets == 1);
}

TEST_CASE("a corrupted CRC is reported and the next packet still parses") {
    Bytes bad = build_status(4, 0, Bytes{1, 2});
    bad.back() ^= 0xFF;
    const Bytes good = build_status(5, 0, Bytes{3});
    Bytes stream = bad;
    stream.insert(stream.end(), good.begin(), good.end());
    PacketParser p;
    p.feed(stream);
    auto out = parse_all(p);
    REQUIRE(out.size() >= 2);
    CHECK(out.front().event == PacketParser::Event::crc_mismatch);
    CHECK(out.front().id == 4);
    CHECK(out.back().event == PacketParser::Event::packet);
    CHECK(out.back().packet.id == 5);
}

TEST_CASE("a flipped payload bit is caught by the CRC") {
    Bytes pk = build_instruction(1, Instruction::write, Bytes{0x74, 0x00, 0x00, 0x08, 0x00, 0x00});
    pk[9] ^= 0x01;
    PacketParser p;
    p.feed(pk);
    auto out = parse_all(p);
    REQUIRE_FALSE(out.empty());
    CHECK(out.front().event == PacketParser::Event::crc_mismatch);
}
