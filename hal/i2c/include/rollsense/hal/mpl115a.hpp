// MPL115A2 barometer: register map, coefficient decoding and the datasheet's
// compensation formula. Pure functions, shared by the sensor plugin, the
// `rollsense probe i2c` diagnostic and the device model (which encodes).
//
// Facts (Freescale MPL115A2 datasheet; docs/hardware.md §1):
//   0x00–0x03  Padc, Tadc: 10-bit ADC values left-justified in 16-bit words (>> 6)
//   0x04–0x0B  a0, b1, b2, c12: 16-bit two's-complement words, MSB first
//   0x12       write + one data byte: start a pressure and temperature conversion
//   conversion: 1.6 ms typical, 3 ms maximum
//   a0  = W / 2^3    (sign, 12 integer bits, 3 fraction bits)
//   b1  = W / 2^13   (sign, 2 integer bits, 13 fraction bits)
//   b2  = W / 2^14   (sign, 1 integer bit, 14 fraction bits)
//   c12 = (W >> 2) / 2^22: 14 significant bits (sign + 13 fraction) whose
//         binary point sits 9 zero bits further left; the two lowest bits of
//         the word are always 0. (A widely copied third-party test vector
//         divides by 10^9 here, as if the padding were decimal: it is not.)
//   Pcomp = a0 + (b1 + c12·Tadc)·Padc + b2·Tadc;  kPa = Pcomp·(115 − 50)/1023 + 50
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>

#include "rollsense/status.hpp"

namespace rollsense::hal::mpl115a {

inline constexpr std::uint8_t kAddress = 0x60;
inline constexpr std::uint8_t kRegPadc = 0x00;
inline constexpr std::uint8_t kRegCoefficients = 0x04;
inline constexpr std::uint8_t kRegStartConversion = 0x12;
inline constexpr std::chrono::microseconds kConversionTimeTypical{1600};
inline constexpr std::chrono::microseconds kConversionTimeMax{3000};
inline constexpr double kMinKpa = 50.0;
inline constexpr double kMaxKpa = 115.0;

// The coefficient words exactly as read (two's complement).
struct CoefficientWords {
    std::int16_t a0 = 0, b1 = 0, b2 = 0, c12 = 0;
};

struct Coefficients {
    double a0 = 0, b1 = 0, b2 = 0, c12 = 0;
    CoefficientWords words;
};

// One conversion's result.
struct AdcReading {
    std::uint16_t padc = 0;  // 0..1023
    std::uint16_t tadc = 0;  // 0..1023
};

// Decode the 8 bytes read from register 0x04. Refuses blocks that cannot come
// from a working chip: all 0x00 / all 0xFF (nobody drove the bus, or a stuck
// line) and a c12 word whose two always-zero bits are set.
Result<Coefficients> decode_coefficients(std::span<const std::uint8_t, 8> bytes);
// The inverse, for device models and tests.
std::array<std::uint8_t, 8> encode_coefficients(const CoefficientWords& words);
Coefficients from_words(const CoefficientWords& words);

// Decode the 4 bytes read from register 0x00. Refuses words whose six
// always-zero low bits are set (bus contention or a wrong device at 0x60).
Result<AdcReading> decode_adc(std::span<const std::uint8_t, 4> bytes);
std::array<std::uint8_t, 4> encode_adc(const AdcReading& reading);

// The datasheet's compensated pressure count (0..1023 over 50..115 kPa).
double compensate(const Coefficients& c, double padc, double tadc);
double pcomp_to_kpa(double pcomp);
inline double pressure_kpa(const Coefficients& c, const AdcReading& r) {
    return pcomp_to_kpa(compensate(c, r.padc, r.tadc));
}

// Nominal temperature scale (datasheet: −5.35 counts/°C; the 25 °C count is
// given as 472 in one source and 498 in another). Uncalibrated: use relatively.
inline constexpr double kTadcPerDegC = -5.35;
inline constexpr double kTadcAt25C = 472.0;

// "a0=2009.75 b1=-2.37585 b2=-0.92047 c12=0.00079" for listings.
std::string describe(const Coefficients& c);

}  // namespace rollsense::hal::mpl115a
