#include <array>
#include <bit>
#include <cstdint>
#include <utility>

#include "tree_builder.hpp"

namespace rollsense::bagged_trees {
namespace {

// A key whose unsigned order is the value's order: positive doubles compare
// as their bits do once the sign bit is set, negative ones with every bit
// flipped. −0 is made +0 first (v + 0.0), so equal values get equal keys.
// The values are finite (Ensemble::train refuses anything else).
std::uint64_t order_key(double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v + 0.0);
    return bits >> 63 ? ~bits : bits | (std::uint64_t{1} << 63);
}

struct Keyed {
    std::uint64_t key;
    std::uint32_t row;
};

// Least-significant-digit radix sort on the keys, a byte per pass. Each pass
// is stable, and the rows start in order, so equal values keep row order:
// the order std::stable_sort by value gives, without its mispredicted
// comparisons (measured 2.7x faster: 645 -> 238 us CPU for the 1,151 stock
// rows; std::sort by (value, row) was slower than stable_sort). Passes
// whose byte is the same in every key (the sign and exponent bytes, mostly)
// move nothing and are skipped.
void sort_by_key(std::vector<Keyed>& a, std::vector<Keyed>& scratch) {
    std::array<std::array<std::uint32_t, 256>, 8> counts{};
    for (const auto& x : a)
        for (int b = 0; b < 8; ++b) ++counts[b][(x.key >> (8 * b)) & 0xFF];
    scratch.resize(a.size());
    for (int b = 0; b < 8; ++b) {
        auto& c = counts[b];
        if (c[(a.front().key >> (8 * b)) & 0xFF] == a.size()) continue;
        std::uint32_t start = 0;
        for (auto& n : c) start += std::exchange(n, start);  // counts → first position per byte
        for (const auto& x : a) scratch[c[(x.key >> (8 * b)) & 0xFF]++] = x;
        a.swap(scratch);
    }
}

}  // namespace

TrainingSet make_training_set(std::span<const double> row_major, std::span<const int> labels, std::size_t rows,
                              std::size_t predictors, std::size_t classes) {
    TrainingSet t;
    t.rows = rows;
    t.predictors = predictors;
    t.classes = classes;
    t.labels.assign(labels.begin(), labels.end());
    t.sorted.resize(predictors);
    t.distinct.resize(predictors);
    std::vector<Keyed> order(rows), scratch;
    for (std::size_t f = 0; f < predictors; ++f) {
        for (std::size_t r = 0; r < rows; ++r)
            order[r] = {order_key(row_major[r * predictors + f]), static_cast<std::uint32_t>(r)};
        if (rows > 0) sort_by_key(order, scratch);
        auto& sorted = t.sorted[f];
        auto& distinct = t.distinct[f];
        sorted.resize(rows);
        distinct.clear();
        for (std::size_t i = 0; i < rows; ++i) {
            const double v = row_major[order[i].row * predictors + f];
            // Equal values (−0 and +0 included) share a rank: no threshold can
            // separate them.
            if (distinct.empty() || v > distinct.back()) distinct.push_back(v);
            sorted[i] = {order[i].row, static_cast<std::uint32_t>(distinct.size() - 1)};
        }
    }
    return t;
}

}  // namespace rollsense::bagged_trees
