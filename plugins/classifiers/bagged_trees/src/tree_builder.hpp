// Grows one classification tree on a bootstrap-weighted view of a training set.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rollsense/bagged_trees/tree.hpp"
#include "rollsense/random.hpp"

namespace rollsense::bagged_trees {

// Shared, read-only by every builder thread: each feature's rows sorted once,
// with values replaced by their rank among the feature's distinct values.
// Ranks compare exactly as the values do, are 4 bytes instead of 8, and the
// value itself is only needed when a split's threshold is written.
struct TrainingSet {
    struct Sorted {
        std::uint32_t row;
        std::uint32_t rank;  // index into `distinct` of the predictor
    };
    std::size_t rows = 0;
    std::size_t predictors = 0;
    std::size_t classes = 0;
    std::vector<std::int32_t> labels;              // rows
    std::vector<std::vector<Sorted>> sorted;       // per predictor: rows by ascending value (stable)
    std::vector<std::vector<double>> distinct;     // per predictor: distinct values, ascending
};

TrainingSet make_training_set(std::span<const double> row_major, std::span<const int> labels, std::size_t rows,
                              std::size_t predictors, std::size_t classes);

// One per thread; keeps its buffers across trees, so growing a tree allocates
// only the tree's own arrays.
class TreeBuilder {
public:
    explicit TreeBuilder(const TrainingSet& data);
    // `weights[r]` = how often row r is in the bootstrap sample (0 = out of bag).
    Tree build(std::span<const std::uint32_t> weights, const TreeOptions& options, random::Xoshiro256ss& rng);

private:
    // One in-bag row in a feature's sorted order, carrying everything the
    // split sweep needs, so the sweep reads one sequential stream.
    struct Entry {
        std::uint32_t rank;
        std::uint32_t row;
        std::uint32_t label;
        std::uint32_t weight;  // bootstrap copies of the row
    };
    struct Split {
        bool found = false;
        std::size_t feature = 0;
        std::size_t left_count = 0;  // in-bag distinct rows going left
        double score = 0.0;
    };
    // A node waiting to be split: its rows are entries [begin, end) of every
    // feature's block in buffer `depth % 2`; its class counts are at
    // node_counts_[queue position * classes].
    struct Pending {
        std::size_t node, begin, end, depth;
        std::int64_t total;  // bootstrap weight in the node
    };

    Split best_split(std::size_t buffer, std::size_t begin, std::size_t count, const std::int64_t* counts,
                     std::int64_t total, const TreeOptions& options, random::Xoshiro256ss& rng);
    template <bool Exact>
    void sweep_gini(std::size_t f, const Entry* e, std::size_t count, const std::int64_t* counts, std::int64_t total,
                    std::int64_t sq_parent, std::int64_t min_leaf, Split& best);
    template <SplitCriterion C>
    void sweep_real(std::size_t f, const Entry* e, std::size_t count, const std::int64_t* counts, double total,
                    double h_parent, double min_leaf, Split& best);
    // Stable partition of every feature's segment into left | right, from
    // one buffer into the other.
    void partition(const Pending& node, const Split& split);
    bool terminal(const std::int64_t* counts, std::int64_t total, const TreeOptions& options) const;

    Entry* block(std::size_t buffer, std::size_t f) { return buffers_[buffer].data() + f * in_bag_; }

    const TrainingSet& data_;
    std::size_t in_bag_ = 0;
    // Two copies of predictors × in_bag entries: a level of the tree reads one
    // and writes its children's order into the other (no copy back).
    std::vector<Entry> buffers_[2];
    std::vector<std::uint8_t> goes_left_;   // per row, for the node being partitioned
    std::vector<std::int64_t> left_;        // class counts left of the sweep position
    std::vector<double> left_real_, right_real_;
    std::vector<std::int64_t> node_counts_;  // class counts of queued nodes
    std::vector<Pending> queue_;
    std::vector<std::size_t> feature_pool_;
};

}  // namespace rollsense::bagged_trees
