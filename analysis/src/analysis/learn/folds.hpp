// Fold partitions for cross-validation.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::learn {

// fold[i] in [0, k) for every row. Stratified like MATLAB's cvpartition and
// scikit-learn's StratifiedKFold: each class is shuffled with the seed and
// dealt round-robin, continuing across classes so fold sizes differ by at
// most one. k must be in [2, rows].
Result<std::vector<int>> stratified_folds(std::span<const int> labels, int k, std::uint64_t seed);

// Grouped folds: all rows of a group (a session, a rig state) land in one fold,
// so correlated trials never straddle training and test. Stratified as far as
// whole groups allow (like scikit-learn's StratifiedGroupKFold), so that a
// grouped figure differs from a random one by what the groups share, not by
// folds short of a class: groups are shuffled with the seed, taken largest
// first, and each goes to the fold where it adds least to the imbalance of the
// classes' shares (ties: the smallest fold).
Result<std::vector<int>> grouped_folds(std::span<const std::string> groups, std::span<const int> labels, int k,
                                       std::uint64_t seed);

// The partitions of a repeated k-fold CV, made once so that every classifier
// compared is trained and tested on exactly the same rows. Repetition r uses
// seed `first_seed + r`, grouped folds when groups are given.
struct FoldPlan {
    int folds = 0;
    bool grouped = false;
    std::vector<std::uint64_t> seeds;          // one per repetition
    std::vector<std::vector<int>> assignment;  // [repetition][row] → fold in [0, folds)
    std::size_t repeats() const { return assignment.size(); }
};
Result<FoldPlan> make_fold_plan(std::span<const int> labels, const std::vector<std::string>* groups, int k,
                                int repeats, std::uint64_t first_seed);

// Row indices of the training (fold != test_fold) or test (fold == test_fold) part.
std::vector<std::size_t> fold_rows(std::span<const int> folds, int test_fold, bool test);

}  // namespace rollsense::learn
