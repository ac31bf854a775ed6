// A fingerprint of an ensemble's trees (structure, exact thresholds, leaf
// posteriors), independent of the model file format and of byte order.
#pragma once

#include <bit>
#include <cstdint>

#include "rollsense/bagged_trees/ensemble.hpp"

namespace toy {

inline std::uint64_t tree_hash(const rollsense::bagged_trees::Ensemble& e) {
    std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a over little-endian bytes
    auto mix = [&h](std::uint64_t v) {
        for (int i = 0; i < 8; ++i) {
            h ^= (v >> (8 * i)) & 0xFF;
            h *= 0x100000001b3ull;
        }
    };
    for (const auto& t : e.trees()) {
        mix(t.nodes());
        for (std::size_t i = 0; i < t.nodes(); ++i) {
            mix(static_cast<std::uint64_t>(static_cast<std::int64_t>(t.feature[i])));
            mix(std::bit_cast<std::uint64_t>(t.threshold[i]));
            mix(static_cast<std::uint64_t>(static_cast<std::int64_t>(t.child[i])));
        }
        for (double p : t.leaf_probs) mix(std::bit_cast<std::uint64_t>(p));
    }
    return h;
}

}  // namespace toy
