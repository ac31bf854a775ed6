#include "tree_builder.hpp"

#include <algorithm>
#include <cstring>

namespace rollsense::bagged_trees {

TreeBuilder::TreeBuilder(const TrainingSet& data) : data_(data) {
    goes_left_.resize(data.rows);
    left_.resize(data.classes);
    left_real_.resize(data.classes);
    right_real_.resize(data.classes);
    feature_pool_.resize(data.predictors);
}

// A node that can never be split, whatever the split budget left.
bool TreeBuilder::terminal(const std::int64_t* counts, std::int64_t total, const TreeOptions& opt) const {
    std::size_t nonzero = 0;
    for (std::size_t c = 0; c < data_.classes; ++c) nonzero += counts[c] > 0;
    return nonzero <= 1 || total < opt.min_parent_size || total < 2 * std::int64_t{std::max(1, opt.min_leaf_size)};
}

void TreeBuilder::partition(const Pending& node, const Split& split) {
    const std::size_t src = node.depth % 2, dst = 1 - src;
    const std::size_t count = node.end - node.begin;
    for (std::size_t f = 0; f < data_.predictors; ++f) {
        const Entry* in = block(src, f) + node.begin;
        Entry* out = block(dst, f) + node.begin;
        if (f == split.feature) {  // already ordered left | right
            std::memcpy(out, in, count * sizeof(Entry));
            continue;
        }
        // Both children's final positions are known (left from 0, right from
        // left_count), so each entry is stored once, at an index chosen
        // without a branch: which side a row goes is unpredictable.
        std::size_t l = 0, r = split.left_count;
        for (std::size_t i = 0; i < count; ++i) {
            const Entry e = in[i];
            const std::size_t gl = goes_left_[e.row];
            out[gl ? l : r] = e;
            l += gl;
            r += 1 - gl;
        }
    }
}

Tree TreeBuilder::build(std::span<const std::uint32_t> weights, const TreeOptions& opt,
                        random::Xoshiro256ss& rng) {
    const std::size_t k = data_.classes, p = data_.predictors;
    std::size_t in_bag = 0;
    double sample_size = 0.0;
    for (std::size_t r = 0; r < data_.rows; ++r) {
        in_bag += weights[r] > 0;
        sample_size += weights[r];
    }
    in_bag_ = in_bag;
    // Sized once for the largest possible bag (every row in it): the bag size
    // changes from tree to tree, and growing would zero and move the buffers.
    // + 1: see the fill below.
    for (auto& b : buffers_)
        if (b.size() < p * in_bag + 1) b.resize(p * data_.rows + 1);
    for (std::size_t f = 0; f < p; ++f) {
        // Branch-free (about a third of the rows is out of bag, at random):
        // every row is written, and the cursor advances only for in-bag rows.
        // An out-of-bag row's write is overwritten by the next in-bag row or,
        // past the block's end, by the next feature's block (filled later) or
        // lands on the buffer's spare last entry.
        Entry* out = block(0, f);
        for (const auto& s : data_.sorted[f]) {
            const std::uint32_t w = weights[s.row];
            *out = {s.rank, s.row, static_cast<std::uint32_t>(data_.labels[s.row]), w};
            out += w > 0;
        }
    }
    const double max_splits =
        opt.max_num_splits > 0 ? static_cast<double>(opt.max_num_splits) : std::max(1.0, sample_size - 1.0);

    queue_.clear();  // breadth-first, like MATLAB's layer-wise growth
    node_counts_.assign(k, 0);
    std::int64_t root_total = 0;
    for (std::size_t r = 0; r < data_.rows; ++r) {
        node_counts_[static_cast<std::size_t>(data_.labels[r])] += weights[r];
        root_total += weights[r];
    }
    queue_.push_back({0, 0, in_bag, 0, root_total});

    Tree t;
    t.feature.push_back(-1);
    t.threshold.push_back(0.0);
    t.child.push_back(0);
    std::size_t splits = 0, leaves = 0;
    for (std::size_t head = 0; head < queue_.size(); ++head) {
        const Pending node = queue_[head];
        const std::int64_t* counts = node_counts_.data() + head * k;
        Split split;
        if (!terminal(counts, node.total, opt) && static_cast<double>(splits) < max_splits)
            split = best_split(node.depth % 2, node.begin, node.end - node.begin, counts, node.total, opt, rng);
        if (!split.found) {
            t.child[node.node] = static_cast<std::int32_t>(leaves++);
            const double total = static_cast<double>(node.total);
            for (std::size_t c = 0; c < k; ++c) t.leaf_probs.push_back(static_cast<double>(counts[c]) / total);
            continue;
        }
        ++splits;

        // Threshold halfway between the values either side of the cut.
        const Entry* chosen = block(node.depth % 2, split.feature) + node.begin;
        const auto& values = data_.distinct[split.feature];
        const double xv = values[chosen[split.left_count - 1].rank];
        const double xn = values[chosen[split.left_count].rank];
        double threshold = 0.5 * (xv + xn);
        if (!(threshold > xv)) threshold = xn;  // adjacent doubles: keep xv < threshold <= xn

        // Children's class counts, and which rows go left.
        const std::size_t count = node.end - node.begin;
        node_counts_.resize(node_counts_.size() + 2 * k);
        std::int64_t* left_counts = node_counts_.data() + node_counts_.size() - 2 * k;
        std::int64_t* right_counts = left_counts + k;
        counts = node_counts_.data() + head * k;  // the resize may have moved it
        std::fill(left_counts, left_counts + k, 0);
        std::int64_t left_total = 0;
        for (std::size_t i = 0; i < count; ++i) {
            const bool left = i < split.left_count;
            goes_left_[chosen[i].row] = left;
            if (left) {
                left_counts[chosen[i].label] += chosen[i].weight;
                left_total += chosen[i].weight;
            }
        }
        for (std::size_t c = 0; c < k; ++c) right_counts[c] = counts[c] - left_counts[c];
        const std::int64_t right_total = node.total - left_total;
        // Children that will be leaves need no ordered rows: when both are,
        // skip the partition (most splits near the bottom of a grown-out tree).
        if (!terminal(left_counts, left_total, opt) || !terminal(right_counts, right_total, opt))
            partition(node, split);

        const std::size_t left = t.feature.size();
        t.feature[node.node] = static_cast<std::int32_t>(split.feature);
        t.threshold[node.node] = threshold;
        t.child[node.node] = static_cast<std::int32_t>(left);
        for (int j = 0; j < 2; ++j) {
            t.feature.push_back(-1);
            t.threshold.push_back(0.0);
            t.child.push_back(0);
        }
        const std::size_t mid = node.begin + split.left_count;
        queue_.push_back({left, node.begin, mid, node.depth + 1, left_total});
        queue_.push_back({left + 1, mid, node.end, node.depth + 1, right_total});
    }
    return t;
}

}  // namespace rollsense::bagged_trees
