// A small, portable random number generator for the simulation.
//
// Why not <random>: std::normal_distribution and friends are implementation-
// defined, so the same seed would give different trials on another standard
// library. Reproducibility across machines is part of the plugin's contract
// (a dataset is identified by its run seed), so the generator and its
// distributions are spelled out here: splitmix64 to expand seeds, xoshiro256**
// for the stream, Box–Muller for normals.
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>

namespace rollsense::sim {

// splitmix64 step: a good bijective mixer, used to derive independent seeds.
inline std::uint64_t mix64(std::uint64_t x) noexcept {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// FNV-1a of a label, so that every random "stream" (noise, start position, ...)
// has its own seed derived from the trial seed and a name. Adding a stream
// later therefore does not shift the draws of the existing ones.
inline std::uint64_t label_hash(std::string_view label) noexcept {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (char c : label) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ull;
    }
    return h;
}

class Rng {
public:
    explicit Rng(std::uint64_t seed = 0) noexcept { reseed(seed); }
    Rng(std::uint64_t seed, std::string_view stream) noexcept { reseed(mix64(seed) ^ label_hash(stream)); }

    void reseed(std::uint64_t seed) noexcept {
        std::uint64_t x = seed;
        for (auto& word : s_) {
            x = mix64(x);
            word = x;
        }
        has_spare_ = false;
    }

    std::uint64_t next() noexcept {
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

    // Uniform in [0, 1) with 53 random bits.
    double uniform() noexcept { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }

    // Standard normal (Box–Muller; the second value of each pair is kept).
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
    static std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }
    std::uint64_t s_[4]{};
    double spare_ = 0.0;
    bool has_spare_ = false;
};

}  // namespace rollsense::sim
