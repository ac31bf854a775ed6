// Grows one classification tree on a bootstrap-weighted view of a training set.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rollsense/bagged_trees/rng.hpp"
#include "rollsense/bagged_trees/tree.hpp"

namespace rollsense::bagged_trees {

// Shared, read-only by every builder thread: the data column-major and each
// feature's row order sorted once.
struct TrainingSet {
    std::size_t rows = 0;
    std::size_t predictors = 0;
    std::size_t classes = 0;
    std::vector<double> columns;                      // predictors × rows
    std::vector<std::int32_t> labels;                 // rows
    std::vector<std::vector<std::uint32_t>> sorted;   // per predictor: rows by ascending value

    const double* column(std::size_t f) const { return columns.data() + f * rows; }
};

TrainingSet make_training_set(std::span<const double> row_major, std::span<const int> labels, std::size_t rows,
                              std::size_t predictors, std::size_t classes);

// One per thread; keeps its buffers across trees.
class TreeBuilder {
public:
    explicit TreeBuilder(const TrainingSet& data);
    // `weights[r]` = how often row r is in the bootstrap sample (0 = out of bag).
    Tree build(std::span<const std::uint32_t> weights, const TreeOptions& options, Rng& rng);

private:
    struct Split {
        bool found = false;
        std::size_t feature = 0;
        std::size_t left_count = 0;  // in-bag distinct rows going left
        double threshold = 0.0;
        double score = 0.0;
    };
    // One in-bag row in a feature's sorted order, carrying what the split
    // sweep needs, so the sweep reads memory sequentially instead of
    // gathering value, label and weight from three arrays.
    struct Entry {
        double x;
        std::uint32_t row;
        std::uint32_t label;
        std::uint32_t weight;
        std::uint32_t pad;
    };
    Split best_split(std::size_t begin, std::size_t end, const std::vector<double>& counts, double total,
                     const TreeOptions& options, Rng& rng);
    template <SplitCriterion C>
    void sweep(std::size_t f, std::size_t begin, std::size_t end, const std::vector<double>& counts, double total,
               double sq_parent, double h_parent, double min_leaf, Split& best);
    void partition(std::size_t begin, std::size_t end, const Split& split);

    const TrainingSet& data_;
    std::span<const std::uint32_t> weights_;
    std::vector<std::vector<Entry>> order_;  // per predictor, in-bag rows; node = segment
    std::vector<std::uint8_t> goes_left_;
    std::vector<Entry> scratch_;
    std::vector<double> left_, right_, counts_;
    std::vector<std::size_t> feature_pool_;
};

}  // namespace rollsense::bagged_trees
