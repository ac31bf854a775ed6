// One classification tree in flat arrays, and the options that grow it
// (MATLAB fitctree semantics as used by fitcensemble 'Bag').
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::bagged_trees {

enum class SplitCriterion {
    gdi,       // Gini's diversity index (MATLAB's default, scikit-learn's "gini")
    deviance,  // cross-entropy
    twoing,    // Breiman's twoing rule
};
std::string_view to_string(SplitCriterion c) noexcept;
Result<SplitCriterion> parse_split_criterion(std::string_view text);

struct TreeOptions {
    int min_leaf_size = 1;         // MATLAB MinLeafSize: observations (bootstrap copies count) per leaf
    int min_parent_size = 2;       // MATLAB MinParentSize: a node with fewer is not split
    int max_num_splits = 0;        // MATLAB MaxNumSplits; 0 = n − 1 (grown out)
    int predictors_per_split = 0;  // 0 = all predictors ('all'); −1 = ceil(sqrt(p)); k = k at random
    SplitCriterion criterion = SplitCriterion::gdi;
};

// Nodes in breadth-first order. An inner node sends x[feature] < threshold to
// child `child` and everything else to `child + 1`; a leaf (feature < 0) keeps
// its class posterior at leaf_probs[child * classes …].
struct Tree {
    std::vector<std::int32_t> feature;
    std::vector<double> threshold;
    std::vector<std::int32_t> child;
    std::vector<double> leaf_probs;

    std::size_t nodes() const { return feature.size(); }
    std::size_t leaves() const;

    // The leaf's class posterior for one observation (classes entries).
    const double* leaf(std::span<const double> x, std::size_t classes) const {
        std::size_t i = 0;
        while (feature[i] >= 0)
            i = static_cast<std::size_t>(child[i]) +
                (x[static_cast<std::size_t>(feature[i])] < threshold[i] ? 0u : 1u);
        return leaf_probs.data() + static_cast<std::size_t>(child[i]) * classes;
    }
};

}  // namespace rollsense::bagged_trees
