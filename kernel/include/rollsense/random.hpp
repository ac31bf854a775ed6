// Seeded random numbers that are the same on every machine.
//
// Why not <random>: std::uniform_int_distribution, std::normal_distribution and friends are implementation-defined,
// so the same seed draws different numbers with another standard library. A simulated dataset is identified by its
// run seed and a trained model by its seed, so the generator and its distributions are spelled out here, once, for
// every plugin:
//   - splitmix64 (Steele, Lea, Flood 2014) to turn seeds into state,
//   - xoshiro256** (Blackman, Vigna 2018) for the stream,
//   - Lemire's multiply-shift for integers below n, 53-bit uniform doubles, Box–Muller for normals.
//
// Two ways of filling the state exist because recorded datasets and trained models depend on each; both are kept
// bit-for-bit and named for what they do:
//   splitmix64_sequence  state words = successive outputs of a splitmix64 generator (Vigna's recommendation; the
//                        bagged trees' numbered streams),
//   splitmix64_chain     each word = splitmix64 of the previous word (the sim sensor's named streams).
// Header-only: plugins get it through the SDK include path without a symbol to export.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace rollsense::random {

// splitmix64's increment (2^64 / golden ratio): a splitmix64 generator's state advances by it, and its n-th output
// is splitmix64(seed + n·gamma).
inline constexpr std::uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;

// splitmix64's output for counter value x: add the golden gamma, then the finaliser. A bijective mixer, used to
// derive independent seeds.
constexpr std::uint64_t splitmix64(std::uint64_t x) noexcept {
    x += kGoldenGamma;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// FNV-1a (64-bit) of a label: gives every named stream its own seed, so adding a stream later does not shift the
// draws of the existing ones.
constexpr std::uint64_t fnv1a64(std::string_view label) noexcept {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (char c : label) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ull;
    }
    return h;
}

// Integer in [0, n), n > 0, from one 64-bit draw: the high word of draw · n
// (Lemire). Not debiased: the bias is below n / 2^64, and it stays one draw per call.
constexpr std::uint64_t scale_below(std::uint64_t draw, std::uint64_t n) noexcept {
    __extension__ using u128 = unsigned __int128;
    return static_cast<std::uint64_t>((static_cast<u128>(draw) * n) >> 64);
}

// Uniform in [0, 1) from the top 53 bits of one 64-bit draw.
constexpr double unit_interval(std::uint64_t draw) noexcept { return static_cast<double>(draw >> 11) * 0x1.0p-53; }

// A splitmix64 generator: output n is splitmix64(seed + n·gamma). One word of state; for fold shuffles and device
// models' draws, where xoshiro's longer period is not needed.
class SplitMix64 {
public:
    explicit constexpr SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
    constexpr std::uint64_t next() noexcept {
        const std::uint64_t z = splitmix64(state_);
        state_ += kGoldenGamma;
        return z;
    }
    constexpr std::uint64_t below(std::uint64_t n) noexcept { return scale_below(next(), n); }
    constexpr double uniform() noexcept { return unit_interval(next()); }

private:
    std::uint64_t state_;
};

class Xoshiro256ss {
public:
    // The raw state (not all zero), e.g. to check against the reference implementation's published outputs.
    static constexpr Xoshiro256ss from_state(std::uint64_t s0, std::uint64_t s1, std::uint64_t s2,
                                             std::uint64_t s3) noexcept {
        Xoshiro256ss g;
        g.s_ = {s0, s1, s2, s3};
        return g;
    }
    // State = the first four outputs of a splitmix64 generator started at `seed`.
    static constexpr Xoshiro256ss splitmix64_sequence(std::uint64_t seed) noexcept {
        Xoshiro256ss g;
        for (std::uint64_t i = 0; i < 4; ++i) g.s_[i] = splitmix64(seed + i * kGoldenGamma);
        return g;
    }
    // State word i = splitmix64(word i − 1), word 0 = splitmix64(seed).
    static constexpr Xoshiro256ss splitmix64_chain(std::uint64_t seed) noexcept {
        Xoshiro256ss g;
        std::uint64_t x = seed;
        for (auto& word : g.s_) word = x = splitmix64(x);
        return g;
    }
    // Stream `index` of `seed` (e.g. one per tree): depends on nothing else, so work split over threads draws the
    // same numbers. Sequence-seeded.
    static constexpr Xoshiro256ss numbered_stream(std::uint64_t seed, std::uint64_t index) noexcept {
        return splitmix64_sequence(splitmix64(seed) ^ splitmix64(index ^ 0xD1B54A32D192ED03ull));
    }
    // Stream `name` of `seed` (e.g. "noise-ch1"): chain-seeded.
    static constexpr Xoshiro256ss named_stream(std::uint64_t seed, std::string_view name) noexcept {
        return splitmix64_chain(splitmix64(seed) ^ fnv1a64(name));
    }

    constexpr std::uint64_t next() noexcept {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }

    // Integer in [0, n), n > 0 (scale_below), and uniform in [0, 1) with 53 random bits.
    constexpr std::uint64_t below(std::uint64_t n) noexcept { return scale_below(next(), n); }
    constexpr double uniform() noexcept { return unit_interval(next()); }
    constexpr double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }

    // Standard normal (Box–Muller; the second value of each pair is kept for the next call).
    double normal() noexcept {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
        const double u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        const double a = 6.283185307179586 * u2;
        spare_ = r * std::sin(a);
        has_spare_ = true;
        return r * std::cos(a);
    }
    double normal(double mean, double sigma) noexcept { return mean + sigma * normal(); }

private:
    static constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }

    std::array<std::uint64_t, 4> s_{};
    double spare_ = 0.0;
    bool has_spare_ = false;
};

}  // namespace rollsense::random
