// Register packing: every format round-trips and shares registers politely.
#include <catch2/catch.hpp>

#include <vector>

#include "register_field.hpp"

using namespace rollsense::modbus;

TEST_CASE("32-bit values: high word first, or swapped") {
    std::vector<std::uint16_t> block(4, 0);
    RegisterField f{1, Format::s32, 1.0, 0.0};
    f.encode_raw(-2, block, 0);
    CHECK(block[1] == 0xFFFF);
    CHECK(block[2] == 0xFFFE);
    CHECK(f.decode_raw(block, 0) == -2);
    RegisterField g{1, Format::u32_swapped, 1.0, 0.0};
    g.encode_raw(0x12345678, block, 0);
    CHECK(block[1] == 0x5678);
    CHECK(block[2] == 0x1234);
    CHECK(g.decode_raw(block, 0) == 0x12345678);
    RegisterField h{1, Format::u32, 1.0, 0.0};
    CHECK(h.decode_raw(block, 0) == 0x56781234);
}

TEST_CASE("byte fields leave the other half of their register alone") {
    std::vector<std::uint16_t> block{0x0900, 0x0000, 0xFFFF};
    RegisterField pos{1001, Format::u8_low, 1.0, 0.0};
    pos.encode_raw(0xAB, block, 1000);
    CHECK(block[1] == 0x00AB);
    RegisterField speed{1002, Format::u8_high, 1.0, 0.0};
    speed.encode_raw(0x10, block, 1000);
    CHECK(block[2] == 0x10FF);
    CHECK(speed.decode_raw(block, 1000) == 0x10);
    CHECK(RegisterField{1000, Format::u8_high, 1, 0}.decode_raw(block, 1000) == 0x09);
}

TEST_CASE("scaling converts units both ways and refuses values the format cannot hold") {
    // A Robotiq-style opening: 85 mm at count 0, 0 mm at count 255.
    RegisterField f{0, Format::u8_low, -85.0 / 255.0, 85.0};
    CHECK(f.to_raw(85.0) == 0);
    CHECK(f.to_raw(0.0) == 255);
    CHECK(f.to_raw(42.5) == 128);  // 127.5 rounds away from zero
    CHECK_FALSE(f.to_raw(90.0).has_value());
    std::vector<std::uint16_t> block{200};
    CHECK(f.decode(block, 0) == Approx(85.0 - 200 * 85.0 / 255.0));
    RegisterField s{0, Format::s16, 0.01, 0.0};
    CHECK(s.to_raw(-12.34) == -1234);
    CHECK_FALSE(s.to_raw(400.0).has_value());  // 40000 > 32767
}

TEST_CASE("formats parse by name") {
    for (const auto& n : format_names()) CHECK(parse_format(n).ok());
    CHECK_FALSE(parse_format("float32").ok());
}
