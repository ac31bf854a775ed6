#include "analysis/learn/folds.hpp"

#include <algorithm>
#include <map>

#include "analysis/learn/random.hpp"

namespace rollsense::learn {

Result<std::vector<int>> stratified_folds(std::span<const int> labels, int k, std::uint64_t seed) {
    if (k < 2) return Error{ErrorCode::invalid_argument, "cross-validation needs at least 2 folds, got " + std::to_string(k)};
    if (static_cast<std::size_t>(k) > labels.size())
        return Error{ErrorCode::invalid_argument, std::to_string(k) + " folds need at least " + std::to_string(k) +
                                                      " trials; there are " + std::to_string(labels.size()) +
                                                      " (fewer folds, or more trials)"};
    std::map<int, std::vector<std::size_t>> by_class;
    for (std::size_t i = 0; i < labels.size(); ++i) by_class[labels[i]].push_back(i);
    SplitMix rng(seed);
    std::vector<int> fold(labels.size(), 0);
    std::size_t dealt = 0;
    for (auto& [label, rows] : by_class) {
        rng.shuffle(rows);
        for (std::size_t r : rows) fold[r] = static_cast<int>(dealt++ % static_cast<std::size_t>(k));
    }
    return fold;
}

Result<std::vector<int>> grouped_folds(std::span<const std::string> groups, std::span<const int> labels, int k,
                                       std::uint64_t seed) {
    if (k < 2) return Error{ErrorCode::invalid_argument, "cross-validation needs at least 2 folds"};
    if (groups.size() != labels.size())
        return Error{ErrorCode::invalid_argument, "grouped folds: " + std::to_string(groups.size()) + " groups for " +
                                                      std::to_string(labels.size()) + " rows"};
    std::map<std::string, std::vector<std::size_t>> by_group;
    std::map<int, double> class_rows;
    for (std::size_t i = 0; i < groups.size(); ++i) {
        by_group[groups[i]].push_back(i);
        ++class_rows[labels[i]];
    }
    if (by_group.size() < static_cast<std::size_t>(k))
        return Error{ErrorCode::invalid_argument, std::to_string(k) + " grouped folds need at least " +
                                                      std::to_string(k) + " groups; there are " +
                                                      std::to_string(by_group.size()) +
                                                      " (fewer folds, or more groups)"};
    std::vector<const std::vector<std::size_t>*> order;
    for (const auto& [name, rows] : by_group) order.push_back(&rows);
    SplitMix rng(seed);
    rng.shuffle(order);
    // Largest groups first keeps the folds balanced (stable for equal sizes).
    std::stable_sort(order.begin(), order.end(), [](auto* a, auto* b) { return a->size() > b->size(); });
    const auto folds = static_cast<std::size_t>(k);
    std::vector<std::size_t> size(folds, 0);
    std::vector<std::map<int, double>> held(folds);  // rows of each class a fold holds
    std::vector<int> fold(groups.size(), 0);
    for (const auto* rows : order) {
        std::map<int, double> adds;
        for (std::size_t r : *rows) ++adds[labels[r]];
        // What the group adds to the fold's imbalance: the growth of the sum over
        // classes of (the class's share in this fold)². A group of one class then
        // goes where that class is scarcest, a mixed group where it fits best.
        const auto growth = [&](std::size_t f) {
            double g = 0.0;
            for (const auto& [label, n] : adds) g += n * (2.0 * held[f][label] + n) / (class_rows[label] * class_rows[label]);
            return g;
        };
        std::size_t best = 0;
        for (std::size_t f = 1; f < folds; ++f) {
            const double gf = growth(f), gb = growth(best);
            if (gf < gb || (gf == gb && size[f] < size[best])) best = f;
        }
        for (std::size_t r : *rows) fold[r] = static_cast<int>(best);
        for (const auto& [label, n] : adds) held[best][label] += n;
        size[best] += rows->size();
    }
    return fold;
}

Result<FoldPlan> make_fold_plan(std::span<const int> labels, const std::vector<std::string>* groups, int k,
                                int repeats, std::uint64_t first_seed) {
    if (repeats < 1)
        return Error{ErrorCode::invalid_argument, "cross-validation needs at least 1 repetition, got " +
                                                      std::to_string(repeats)};
    FoldPlan plan;
    plan.folds = k;
    plan.grouped = groups != nullptr;
    for (int rep = 0; rep < repeats; ++rep) {
        const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(rep);
        auto f = groups ? grouped_folds(*groups, labels, k, seed) : stratified_folds(labels, k, seed);
        if (!f) return f.error();
        plan.seeds.push_back(seed);
        plan.assignment.push_back(std::move(f).value());
    }
    return plan;
}

std::vector<std::size_t> fold_rows(std::span<const int> folds, int test_fold, bool test) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < folds.size(); ++i)
        if ((folds[i] == test_fold) == test) out.push_back(i);
    return out;
}

}  // namespace rollsense::learn
