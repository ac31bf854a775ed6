// Coefficient and ADC decoding, and the compensation formula, against values
// computed by hand from the datasheet's definitions (hardware.md §1).
#include <catch2/catch.hpp>

#include <array>

#include "rollsense/hal/mpl115a.hpp"

using namespace rollsense;
namespace ms = rollsense::hal::mpl115a;

TEST_CASE("coefficients of the datasheet example decode exactly", "[mpl115a][codec]") {
    // Freescale AN3785's example chip: a0 0x3ECE, b1 0xB3F9, b2 0xC517, c12 0x33C8.
    const std::array<std::uint8_t, 8> raw{0x3e, 0xce, 0xb3, 0xf9, 0xc5, 0x17, 0x33, 0xc8};
    auto c = ms::decode_coefficients(raw);
    REQUIRE(c.ok());
    CHECK(c->a0 == 2009.75);                      // 16078 / 2^3
    CHECK(c->b1 == -19463.0 / 8192.0);            // 0xB3F9 = −19463 → −2.3758544921875
    CHECK(c->b2 == -15081.0 / 16384.0);           // 0xC517 = −15081 → −0.92047119140625
    CHECK(c->c12 == 3314.0 / 4194304.0);          // (13256 >> 2) / 2^22 = 0.000790119...
    CHECK(c->words.c12 == 0x33c8);
    // The widely copied wrong vector treats the 9 padding bits as decimal
    // digits (3314 / 10^9); ours must not be that.
    CHECK(c->c12 != Approx(3314e-9));
}

TEST_CASE("negative coefficients keep their sign, including c12", "[mpl115a][codec]") {
    SECTION("most negative words") {
        const std::array<std::uint8_t, 8> raw{0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00};
        auto c = ms::decode_coefficients(raw);
        REQUIRE(c.ok());
        CHECK(c->a0 == -4096.0);        // −32768 / 8
        CHECK(c->b1 == -4.0);           // −32768 / 8192
        CHECK(c->b2 == -2.0);           // −32768 / 16384
        CHECK(c->c12 == -0.001953125);  // (−32768 >> 2) / 2^22 = −8192 / 4194304
    }
    SECTION("minus one LSB") {
        // c12 0xFFFC: the word is −4, its 14 significant bits are −1.
        const std::array<std::uint8_t, 8> raw{0xff, 0xff, 0xff, 0xff, 0xff, 0xfe, 0xff, 0xfc};
        auto c = ms::decode_coefficients(raw);
        REQUIRE(c.ok());
        CHECK(c->a0 == -0.125);
        CHECK(c->b1 == -1.0 / 8192.0);
        CHECK(c->b2 == -2.0 / 16384.0);
        CHECK(c->c12 == -1.0 / 4194304.0);
    }
    SECTION("largest positive c12") {
        const std::array<std::uint8_t, 8> raw{0x10, 0x00, 0x00, 0x01, 0x00, 0x01, 0x7f, 0xfc};
        auto c = ms::decode_coefficients(raw);
        REQUIRE(c.ok());
        CHECK(c->a0 == 512.0);
        CHECK(c->c12 == 8191.0 / 4194304.0);
    }
}

TEST_CASE("coefficient blocks no working chip produces are refused", "[mpl115a][codec]") {
    std::array<std::uint8_t, 8> ones{};
    ones.fill(0xff);
    auto r1 = ms::decode_coefficients(ones);
    REQUIRE_FALSE(r1.ok());
    CHECK(r1.error().code == ErrorCode::protocol_error);
    CHECK_THAT(r1.error().message, Catch::Contains("0xFF"));

    std::array<std::uint8_t, 8> zeros{};
    auto r0 = ms::decode_coefficients(zeros);
    REQUIRE_FALSE(r0.ok());
    CHECK_THAT(r0.error().message, Catch::Contains("0x00"));

    // c12's two lowest bits are always 0 on a real chip.
    const std::array<std::uint8_t, 8> bad_c12{0x3e, 0xce, 0xb3, 0xf9, 0xc5, 0x17, 0x33, 0xc9};
    auto rc = ms::decode_coefficients(bad_c12);
    REQUIRE_FALSE(rc.ok());
    CHECK_THAT(rc.error().message, Catch::Contains("c12"));
}

TEST_CASE("coefficients round-trip through encoding", "[mpl115a][codec]") {
    ms::CoefficientWords w{-1234, -19463, 321, -8192 * 4 + 4};
    auto bytes = ms::encode_coefficients(w);
    auto c = ms::decode_coefficients(bytes);
    REQUIRE(c.ok());
    CHECK(c->words.a0 == w.a0);
    CHECK(c->words.b1 == w.b1);
    CHECK(c->words.b2 == w.b2);
    CHECK(c->words.c12 == w.c12);
}

TEST_CASE("ADC words are 10 bits left-justified", "[mpl115a][codec]") {
    // Datasheet example: Padc 0x6680 → 410, Tadc 0x7EC0 → 507.
    const std::array<std::uint8_t, 4> raw{0x66, 0x80, 0x7e, 0xc0};
    auto r = ms::decode_adc(raw);
    REQUIRE(r.ok());
    CHECK(r->padc == 410);
    CHECK(r->tadc == 507);
    CHECK(ms::encode_adc(*r) == raw);

    const std::array<std::uint8_t, 4> full{0xff, 0xc0, 0x00, 0x00};
    auto f = ms::decode_adc(full);
    REQUIRE(f.ok());
    CHECK(f->padc == 1023);
    CHECK(f->tadc == 0);

    // Low six bits set: not an MPL115A word (e.g. a bus with nobody driving it).
    const std::array<std::uint8_t, 4> idle{0xff, 0xff, 0xff, 0xff};
    auto bad = ms::decode_adc(idle);
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().code == ErrorCode::protocol_error);
    CHECK_THAT(bad.error().message, Catch::Contains("ff ff ff ff"));
}

TEST_CASE("compensation matches the hand-computed datasheet example", "[mpl115a][compensation]") {
    const std::array<std::uint8_t, 8> raw{0x3e, 0xce, 0xb3, 0xf9, 0xc5, 0x17, 0x33, 0xc8};
    auto c = ms::decode_coefficients(raw);
    REQUIRE(c.ok());
    // By hand, exact in binary fractions:
    //   c12·Tadc = 3314·507 / 2^22            = 0.400590419769287
    //   b1 + c12·Tadc                           = −1.975264072418213
    //   (b1 + c12·Tadc)·Padc = ·410             = −809.858269691467
    //   b2·Tadc = −15081·507 / 16384            = −466.678894042969
    //   Pcomp = 2009.75 − 809.858269691467 − 466.678894042969 = 733.212836265564
    //   kPa = 733.212836265564 · 65/1023 + 50   = 96.5873258624259
    const double pcomp = ms::compensate(*c, 410, 507);
    CHECK(pcomp == Approx(733.212836265564).epsilon(1e-13));
    const double kpa = ms::pressure_kpa(*c, ms::AdcReading{410, 507});
    CHECK(kpa == Approx(96.5873258624259).epsilon(1e-13));
    // The application note's fixed-point arithmetic gives 733.19 → 96.59 kPa.
    CHECK(kpa == Approx(96.59).margin(0.01));
    // Range ends of the transfer function.
    CHECK(ms::pcomp_to_kpa(0) == 50.0);
    CHECK(ms::pcomp_to_kpa(1023) == Approx(115.0));
}
