#include "tree_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rollsense::bagged_trees {

std::string_view to_string(SplitCriterion c) noexcept {
    switch (c) {
        case SplitCriterion::gdi: return "gdi";
        case SplitCriterion::deviance: return "deviance";
        case SplitCriterion::twoing: return "twoing";
    }
    return "?";
}

Result<SplitCriterion> parse_split_criterion(std::string_view text) {
    if (text == "gdi") return SplitCriterion::gdi;
    if (text == "deviance") return SplitCriterion::deviance;
    if (text == "twoing") return SplitCriterion::twoing;
    return Error{ErrorCode::invalid_argument,
                 "unknown split criterion '" + std::string(text) + "' (expected gdi, deviance or twoing)"};
}

std::size_t Tree::leaves() const {
    return static_cast<std::size_t>(std::count_if(feature.begin(), feature.end(), [](auto f) { return f < 0; }));
}

TrainingSet make_training_set(std::span<const double> row_major, std::span<const int> labels, std::size_t rows,
                              std::size_t predictors, std::size_t classes) {
    TrainingSet t;
    t.rows = rows;
    t.predictors = predictors;
    t.classes = classes;
    t.columns.resize(rows * predictors);
    for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t f = 0; f < predictors; ++f) t.columns[f * rows + r] = row_major[r * predictors + f];
    t.labels.assign(labels.begin(), labels.end());
    t.sorted.resize(predictors);
    for (std::size_t f = 0; f < predictors; ++f) {
        auto& s = t.sorted[f];
        s.resize(rows);
        std::iota(s.begin(), s.end(), 0u);
        const double* col = t.column(f);
        std::stable_sort(s.begin(), s.end(), [col](std::uint32_t a, std::uint32_t b) { return col[a] < col[b]; });
    }
    return t;
}

TreeBuilder::TreeBuilder(const TrainingSet& data) : data_(data) {
    order_.resize(data.predictors);
    goes_left_.resize(data.rows);
    left_.resize(data.classes);
    right_.resize(data.classes);
    counts_.resize(data.classes);
    feature_pool_.resize(data.predictors);
}

namespace {

inline double xlogx(double v) { return v > 0.0 ? v * std::log(v) : 0.0; }

}  // namespace

template <SplitCriterion C>
void TreeBuilder::sweep(std::size_t f, std::size_t begin, std::size_t end, const std::vector<double>& counts,
                        double total, double sq_parent, double h_parent, double min_leaf, Split& best) {
    const std::size_t k = data_.classes;
    const Entry* ord = order_[f].data();
    std::fill(left_.begin(), left_.end(), 0.0);
    std::copy(counts.begin(), counts.end(), right_.begin());
    double* left = left_.data();
    double* right = right_.data();
    double wl = 0.0, wr = total;
    double sql = 0.0, sqr = sq_parent;  // Σ count² per side (Gini)
    double hl = 0.0, hr = h_parent;     // Σ count·ln count per side (deviance)
    for (std::size_t i = begin; i + 1 < end; ++i) {
        const Entry& e = ord[i];
        const double rw = static_cast<double>(e.weight);
        const std::size_t c = e.label;
        if constexpr (C == SplitCriterion::gdi) {
            sql += rw * (2.0 * left[c] + rw);
            sqr -= rw * (2.0 * right[c] - rw);
        } else if constexpr (C == SplitCriterion::deviance) {
            hl += xlogx(left[c] + rw) - xlogx(left[c]);
            hr += xlogx(right[c] - rw) - xlogx(right[c]);
        }
        left[c] += rw;
        right[c] -= rw;
        wl += rw;
        wr -= rw;
        const double xv = e.x;
        const double xn = ord[i + 1].x;
        if (!(xn > xv)) continue;  // no threshold between equal values
        if (wl < min_leaf || wr < min_leaf) continue;
        double score = 0.0;
        if constexpr (C == SplitCriterion::gdi) {
            // sql/wl + sqr/wr > best without two divisions per candidate.
            const double den = wl * wr;
            if (!(sql * wr + sqr * wl > best.score * den)) continue;
            score = (sql * wr + sqr * wl) / den;
        } else if constexpr (C == SplitCriterion::deviance) {
            score = hl + hr - xlogx(wl) - xlogx(wr);
        } else {
            double diff = 0.0;
            for (std::size_t j = 0; j < k; ++j) diff += std::abs(left[j] / wl - right[j] / wr);
            score = (wl / total) * (wr / total) * diff * diff / 4.0;
        }
        if (score > best.score) {
            best.found = true;
            best.score = score;
            best.feature = f;
            best.left_count = i + 1 - begin;
            double mid = 0.5 * (xv + xn);
            if (!(mid > xv)) mid = xn;  // adjacent doubles: keep xv < threshold <= xn
            best.threshold = mid;
        }
    }
}

TreeBuilder::Split TreeBuilder::best_split(std::size_t begin, std::size_t end, const std::vector<double>& counts,
                                           double total, const TreeOptions& opt, Rng& rng) {
    const std::size_t p = data_.predictors;
    std::size_t tries = p;
    if (opt.predictors_per_split < 0)
        tries = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(p))));
    else if (opt.predictors_per_split > 0)
        tries = std::min<std::size_t>(p, static_cast<std::size_t>(opt.predictors_per_split));
    std::iota(feature_pool_.begin(), feature_pool_.end(), std::size_t{0});
    if (tries < p) {
        // Partial Fisher–Yates: the first `tries` entries are a uniform sample.
        for (std::size_t i = 0; i < tries; ++i) std::swap(feature_pool_[i], feature_pool_[i + rng.below(p - i)]);
        std::sort(feature_pool_.begin(), feature_pool_.begin() + static_cast<std::ptrdiff_t>(tries));
    }

    const double min_leaf = static_cast<double>(std::max(1, opt.min_leaf_size));
    // The parent's own score, so a split must strictly improve on it.
    double parent = 0.0;
    double sq_parent = 0.0, h_parent = 0.0;
    for (double c : counts) {
        sq_parent += c * c;
        h_parent += xlogx(c);
    }
    switch (opt.criterion) {
        case SplitCriterion::gdi: parent = sq_parent / total; break;
        case SplitCriterion::deviance: parent = h_parent - xlogx(total); break;
        case SplitCriterion::twoing: parent = 0.0; break;
    }
    Split best;
    best.score = parent + 1e-12 * std::max(1.0, std::abs(parent));
    for (std::size_t fi = 0; fi < tries; ++fi) {
        const std::size_t f = feature_pool_[fi];
        switch (opt.criterion) {
            case SplitCriterion::gdi:
                sweep<SplitCriterion::gdi>(f, begin, end, counts, total, sq_parent, h_parent, min_leaf, best);
                break;
            case SplitCriterion::deviance:
                sweep<SplitCriterion::deviance>(f, begin, end, counts, total, sq_parent, h_parent, min_leaf, best);
                break;
            case SplitCriterion::twoing:
                sweep<SplitCriterion::twoing>(f, begin, end, counts, total, sq_parent, h_parent, min_leaf, best);
                break;
        }
    }
    return best;
}

void TreeBuilder::partition(std::size_t begin, std::size_t end, const Split& split) {
    const auto& chosen = order_[split.feature];
    for (std::size_t i = begin; i < end; ++i) goes_left_[chosen[i].row] = i < begin + split.left_count ? 1 : 0;
    scratch_.resize(end - begin);
    for (std::size_t f = 0; f < data_.predictors; ++f) {
        if (f == split.feature) continue;  // already ordered left | right
        auto& ord = order_[f];
        std::size_t l = begin, r = 0;
        // Branch-free: which side a row goes is unpredictable, so write the
        // entry to both places and advance only the matching cursor.
        Entry* out_left = ord.data();
        Entry* out_right = scratch_.data();
        for (std::size_t i = begin; i < end; ++i) {
            const Entry e = ord[i];
            const std::size_t gl = goes_left_[e.row];
            out_left[l] = e;
            out_right[r] = e;
            l += gl;
            r += 1 - gl;
        }
        std::copy(scratch_.begin(), scratch_.begin() + static_cast<std::ptrdiff_t>(r),
                  ord.begin() + static_cast<std::ptrdiff_t>(l));
    }
}

Tree TreeBuilder::build(std::span<const std::uint32_t> weights, const TreeOptions& opt, Rng& rng) {
    weights_ = weights;
    const std::size_t k = data_.classes;
    std::size_t in_bag = 0;
    double sample_size = 0.0;
    for (std::size_t r = 0; r < data_.rows; ++r) {
        in_bag += weights[r] > 0;
        sample_size += weights[r];
    }
    for (std::size_t f = 0; f < data_.predictors; ++f) {
        auto& ord = order_[f];
        ord.clear();
        ord.reserve(in_bag);
        const double* col = data_.column(f);
        for (std::uint32_t r : data_.sorted[f])
            if (weights[r] > 0)
                ord.push_back({col[r], r, static_cast<std::uint32_t>(data_.labels[r]), weights[r], 0});
    }
    const double max_splits =
        opt.max_num_splits > 0 ? static_cast<double>(opt.max_num_splits) : std::max(1.0, sample_size - 1.0);

    Tree t;
    struct Pending {
        std::size_t node, begin, end;
    };
    std::vector<Pending> queue;  // breadth-first, like MATLAB's layer-wise growth
    queue.push_back({0, 0, in_bag});
    t.feature.push_back(-1);
    t.threshold.push_back(0.0);
    t.child.push_back(0);
    std::size_t splits = 0, leaves = 0;
    const auto& any_order = order_[0];
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const Pending node = queue[head];
        std::fill(counts_.begin(), counts_.end(), 0.0);
        double total = 0.0;
        for (std::size_t i = node.begin; i < node.end; ++i) {
            const Entry& e = any_order[i];
            counts_[e.label] += e.weight;
            total += e.weight;
        }
        const bool pure =
            std::count_if(counts_.begin(), counts_.end(), [](double c) { return c > 0.0; }) <= 1;
        Split split;
        if (!pure && total >= static_cast<double>(opt.min_parent_size) &&
            static_cast<double>(splits) < max_splits && total >= 2.0 * std::max(1, opt.min_leaf_size))
            split = best_split(node.begin, node.end, counts_, total, opt, rng);
        if (!split.found) {
            t.child[node.node] = static_cast<std::int32_t>(leaves++);
            for (std::size_t c = 0; c < k; ++c) t.leaf_probs.push_back(counts_[c] / total);
            continue;
        }
        ++splits;
        partition(node.begin, node.end, split);
        const std::size_t left = t.feature.size();
        t.feature[node.node] = static_cast<std::int32_t>(split.feature);
        t.threshold[node.node] = split.threshold;
        t.child[node.node] = static_cast<std::int32_t>(left);
        for (int j = 0; j < 2; ++j) {
            t.feature.push_back(-1);
            t.threshold.push_back(0.0);
            t.child.push_back(0);
        }
        queue.push_back({left, node.begin, node.begin + split.left_count});
        queue.push_back({left + 1, node.begin + split.left_count, node.end});
    }
    return t;
}

}  // namespace rollsense::bagged_trees
