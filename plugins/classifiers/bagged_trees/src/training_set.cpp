#include <algorithm>
#include <utility>

#include "tree_builder.hpp"

namespace rollsense::bagged_trees {

TrainingSet make_training_set(std::span<const double> row_major, std::span<const int> labels, std::size_t rows,
                              std::size_t predictors, std::size_t classes) {
    TrainingSet t;
    t.rows = rows;
    t.predictors = predictors;
    t.classes = classes;
    t.labels.assign(labels.begin(), labels.end());
    t.sorted.resize(predictors);
    t.distinct.resize(predictors);
    // (value, row) pairs, stable-sorted by value: ties stay in row order, and
    // the comparisons read the values in place rather than through the rows.
    std::vector<std::pair<double, std::uint32_t>> order(rows);
    for (std::size_t f = 0; f < predictors; ++f) {
        for (std::size_t r = 0; r < rows; ++r) order[r] = {row_major[r * predictors + f], static_cast<std::uint32_t>(r)};
        std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        auto& sorted = t.sorted[f];
        auto& distinct = t.distinct[f];
        sorted.resize(rows);
        distinct.clear();
        for (std::size_t i = 0; i < rows; ++i) {
            const double v = order[i].first;
            // Equal values (−0 and +0 included) share a rank: no threshold can
            // separate them.
            if (distinct.empty() || v > distinct.back()) distinct.push_back(v);
            sorted[i] = {order[i].second, static_cast<std::uint32_t>(distinct.size() - 1)};
        }
    }
    return t;
}

}  // namespace rollsense::bagged_trees
