#include "rollsense/hal/mpl115a.hpp"

#include <cstdio>

namespace rollsense::hal::mpl115a {
namespace {

std::int16_t word_at(std::span<const std::uint8_t> b, std::size_t i) {
    // MSB first; the cast to int16_t is the two's-complement reinterpretation.
    return static_cast<std::int16_t>(static_cast<std::uint16_t>((b[i] << 8) | b[i + 1]));
}

void put_word(std::uint8_t* out, std::uint16_t w) {
    out[0] = static_cast<std::uint8_t>(w >> 8);
    out[1] = static_cast<std::uint8_t>(w & 0xff);
}

std::string hex_bytes(std::span<const std::uint8_t> b) {
    std::string s;
    char buf[4];
    for (auto v : b) {
        std::snprintf(buf, sizeof buf, "%02x", static_cast<unsigned>(v));
        if (!s.empty()) s += ' ';
        s += buf;
    }
    return s;
}

}  // namespace

Coefficients from_words(const CoefficientWords& w) {
    Coefficients c;
    c.words = w;
    c.a0 = w.a0 / 8.0;
    c.b1 = w.b1 / 8192.0;
    c.b2 = w.b2 / 16384.0;
    // Arithmetic shift of the signed word keeps the sign; 2^22 = 4194304.
    c.c12 = static_cast<double>(w.c12 >> 2) / 4194304.0;
    return c;
}

Result<Coefficients> decode_coefficients(std::span<const std::uint8_t, 8> bytes) {
    bool all_zero = true, all_ones = true;
    for (auto b : bytes) {
        all_zero = all_zero && b == 0x00;
        all_ones = all_ones && b == 0xff;
    }
    if (all_ones)
        return Error{ErrorCode::protocol_error,
                     "coefficients read as all 0xFF: no chip drove the bus (not selected, held in reset, or absent)"};
    if (all_zero)
        return Error{ErrorCode::protocol_error, "coefficients read as all 0x00: SDA held low or the chip is not an MPL115A"};
    CoefficientWords w;
    w.a0 = word_at(bytes, 0);
    w.b1 = word_at(bytes, 2);
    w.b2 = word_at(bytes, 4);
    w.c12 = word_at(bytes, 6);
    if ((bytes[7] & 0x03) != 0)
        return Error{ErrorCode::protocol_error, "c12 word's two always-zero low bits are set (bytes " +
                                                    hex_bytes(bytes) + "): not an MPL115A, or corrupted transfer"};
    return from_words(w);
}

std::array<std::uint8_t, 8> encode_coefficients(const CoefficientWords& w) {
    std::array<std::uint8_t, 8> out{};
    put_word(&out[0], static_cast<std::uint16_t>(w.a0));
    put_word(&out[2], static_cast<std::uint16_t>(w.b1));
    put_word(&out[4], static_cast<std::uint16_t>(w.b2));
    put_word(&out[6], static_cast<std::uint16_t>(w.c12));
    return out;
}

Result<AdcReading> decode_adc(std::span<const std::uint8_t, 4> bytes) {
    const auto p = static_cast<std::uint16_t>((bytes[0] << 8) | bytes[1]);
    const auto t = static_cast<std::uint16_t>((bytes[2] << 8) | bytes[3]);
    if ((p & 0x3f) != 0 || (t & 0x3f) != 0)
        return Error{ErrorCode::protocol_error,
                     "ADC words " + hex_bytes(bytes) +
                         " have their six always-zero low bits set: bus contention (two chips selected?) or a "
                         "device other than an MPL115A at 0x60"};
    return AdcReading{static_cast<std::uint16_t>(p >> 6), static_cast<std::uint16_t>(t >> 6)};
}

std::array<std::uint8_t, 4> encode_adc(const AdcReading& r) {
    std::array<std::uint8_t, 4> out{};
    put_word(&out[0], static_cast<std::uint16_t>((r.padc & 0x3ff) << 6));
    put_word(&out[2], static_cast<std::uint16_t>((r.tadc & 0x3ff) << 6));
    return out;
}

double compensate(const Coefficients& c, double padc, double tadc) {
    return c.a0 + (c.b1 + c.c12 * tadc) * padc + c.b2 * tadc;
}

double pcomp_to_kpa(double pcomp) { return pcomp * ((kMaxKpa - kMinKpa) / 1023.0) + kMinKpa; }

std::string describe(const Coefficients& c) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "a0=%.3f b1=%.5f b2=%.5f c12=%.8f (words %04x %04x %04x %04x)", c.a0, c.b1, c.b2,
                  c.c12, static_cast<unsigned>(static_cast<std::uint16_t>(c.words.a0)),
                  static_cast<unsigned>(static_cast<std::uint16_t>(c.words.b1)),
                  static_cast<unsigned>(static_cast<std::uint16_t>(c.words.b2)),
                  static_cast<unsigned>(static_cast<std::uint16_t>(c.words.c12)));
    return buf;
}

}  // namespace rollsense::hal::mpl115a
