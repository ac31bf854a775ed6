// The best split of one node: for each predictor tried, one sweep over the
// node's rows in that predictor's order, with running class counts.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "tree_builder.hpp"

namespace rollsense::bagged_trees {
namespace {

inline double xlogx(double v) { return v > 0.0 ? v * std::log(v) : 0.0; }

}  // namespace

// Gini (the default, and the hot loop of training). Bootstrap weights are
// whole numbers, so the counts and the sums of squared counts per side are
// kept in integers. A candidate's score is sql/wl + sqr/wr (maximised, which
// minimises the weighted Gini index), computed in double as
// (sql·wr + sqr·wl) / (wl·wr): one division per accepted candidate, the same
// rounding as the builder before it, so the trees are unchanged.
//
// The loop is bound by its work per entry, not by the running count left[c]
// (loading the next class's count ahead of the store, which takes the
// store-to-load wait off the chain, measured slower), so each step is kept
// short:
// - sqr is not kept per step: with d = sq_parent − 2·Σ counts[c]·left[c]
//   (down by 2·w·counts[c] per entry), sqr = d + sql and the numerator
//   sql·wr + sqr·wl is total·sql + wl·d;
// - when every product is below 2^53 (Exact: total < 2^17, so total³ < 2^51)
//   num and den are formed in integers and converted once each: the doubles
//   the old formula formed from four conversions were exact too, so they are
//   the same numbers.
template <bool Exact>
void TreeBuilder::sweep_gini(std::size_t f, const Entry* e, std::size_t count, const std::int64_t* counts,
                             std::int64_t total, std::int64_t sq_parent, std::int64_t min_leaf, Split& best) {
    std::int64_t* left = left_.data();
    std::fill(left_.begin(), left_.end(), 0);
    std::int64_t wl = 0, sql = 0, d = sq_parent;  // left weight, Σ left², sq_parent − 2·Σ counts·left
    auto add_left = [&](const Entry& x) {
        const std::uint32_t c = x.label;
        const std::int64_t w = x.weight;
        const std::int64_t lc = left[c];
        sql += w * (2 * lc + w);
        d -= 2 * (w * counts[c]);
        left[c] = lc + w;
        wl += w;
    };
    // Cuts after entries [first, last] leave at least min_leaf on each side:
    // the leaf-size test stays out of the loop.
    std::size_t i = 0;
    while (i + 1 < count && wl + e[i].weight < min_leaf) add_left(e[i++]);
    std::size_t last = count - 1;  // cut after entry `last` would leave the right side empty
    for (std::int64_t wr = 0; last > i && wr + e[last].weight < min_leaf;) wr += e[last--].weight;
    double best_score = best.score;
    std::size_t best_i = count;
    // Two pure sides score sql/wl + sqr/wr = wl + wr, computed exactly.
    const double perfect = static_cast<double>(total);
    for (; i < last; ++i) {
        add_left(e[i]);
        const std::int64_t wr = total - wl;
        // sql/wl + sqr/wr > best without two divisions per candidate.
        double num, den;
        if constexpr (Exact) {
            num = static_cast<double>(total * sql + wl * d);
            den = static_cast<double>(wl * wr);
        } else {
            const double dl = static_cast<double>(wl), dr = static_cast<double>(wr);
            den = dl * dr;
            num = static_cast<double>(sql) * dr + static_cast<double>(d + sql) * dl;
        }
        // No threshold between equal values. Ties are common in some features
        // and rare in others, so that test is folded without a branch into the
        // (well predicted) test against the best score.
        if (!((num > best_score * den) & (e[i + 1].rank != e[i].rank))) continue;
        const double score = num / den;
        if (score > best_score) {
            best_score = score;
            best_i = i;
            if (score >= perfect) break;  // both sides pure: nothing later can score higher
        }
    }
    if (best_i < count) {
        best.found = true;
        best.score = best_score;
        best.feature = f;
        best.left_count = best_i + 1;
    }
}

// Deviance and twoing: real-valued per-candidate terms, kept in doubles.
template <SplitCriterion C>
void TreeBuilder::sweep_real(std::size_t f, const Entry* e, std::size_t count, const std::int64_t* counts,
                             double total, double h_parent, double min_leaf, Split& best) {
    const std::size_t k = data_.classes;
    double* left = left_real_.data();
    double* right = right_real_.data();
    for (std::size_t c = 0; c < k; ++c) {
        left[c] = 0.0;
        right[c] = static_cast<double>(counts[c]);
    }
    double wl = 0.0, wr = total;
    double hl = 0.0, hr = h_parent;  // Σ count·ln count per side (deviance)
    for (std::size_t i = 0; i + 1 < count; ++i) {
        const double rw = static_cast<double>(e[i].weight);
        const std::size_t c = e[i].label;
        if constexpr (C == SplitCriterion::deviance) {
            hl += xlogx(left[c] + rw) - xlogx(left[c]);
            hr += xlogx(right[c] - rw) - xlogx(right[c]);
        }
        left[c] += rw;
        right[c] -= rw;
        wl += rw;
        wr -= rw;
        if (e[i + 1].rank == e[i].rank) continue;
        if (wl < min_leaf || wr < min_leaf) continue;
        double score = 0.0;
        if constexpr (C == SplitCriterion::deviance) {
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
            best.left_count = i + 1;
        }
    }
}

TreeBuilder::Split TreeBuilder::best_split(std::size_t buffer, std::size_t begin, std::size_t count,
                                           const std::int64_t* counts, std::int64_t total, const TreeOptions& opt,
                                           random::Xoshiro256ss& rng) {
    const std::size_t p = data_.predictors;
    std::size_t tries = p;
    if (opt.predictors_per_split < 0)
        tries = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(p))));
    else if (opt.predictors_per_split > 0)
        tries = std::min<std::size_t>(p, static_cast<std::size_t>(opt.predictors_per_split));
    if (tries < p) {
        // Partial Fisher–Yates: the first `tries` entries are a uniform sample.
        std::iota(feature_pool_.begin(), feature_pool_.end(), std::size_t{0});
        for (std::size_t i = 0; i < tries; ++i) std::swap(feature_pool_[i], feature_pool_[i + rng.below(p - i)]);
        std::sort(feature_pool_.begin(), feature_pool_.begin() + static_cast<std::ptrdiff_t>(tries));
    }

    const std::int64_t min_leaf = std::max(1, opt.min_leaf_size);
    const double dtotal = static_cast<double>(total);
    // The parent's own score, so a split must strictly improve on it.
    std::int64_t sq_parent = 0;
    double h_parent = 0.0, parent = 0.0;
    switch (opt.criterion) {
        case SplitCriterion::gdi:
            for (std::size_t c = 0; c < data_.classes; ++c) sq_parent += counts[c] * counts[c];
            parent = static_cast<double>(sq_parent) / dtotal;
            break;
        case SplitCriterion::deviance:
            for (std::size_t c = 0; c < data_.classes; ++c) h_parent += xlogx(static_cast<double>(counts[c]));
            parent = h_parent - xlogx(dtotal);
            break;
        case SplitCriterion::twoing: parent = 0.0; break;
    }
    Split best;
    best.score = parent + 1e-12 * std::max(1.0, std::abs(parent));
    for (std::size_t fi = 0; fi < tries; ++fi) {
        const std::size_t f = tries < p ? feature_pool_[fi] : fi;
        const Entry* e = block(buffer, f) + begin;
        // Sorted rows with equal first and last values: the feature is
        // constant in this node and offers no threshold.
        if (e[0].rank == e[count - 1].rank) continue;
        switch (opt.criterion) {
            case SplitCriterion::gdi:
                if (total < (std::int64_t{1} << 17))
                    sweep_gini<true>(f, e, count, counts, total, sq_parent, min_leaf, best);
                else
                    sweep_gini<false>(f, e, count, counts, total, sq_parent, min_leaf, best);
                break;
            case SplitCriterion::deviance:
                sweep_real<SplitCriterion::deviance>(f, e, count, counts, dtotal, h_parent,
                                                     static_cast<double>(min_leaf), best);
                break;
            case SplitCriterion::twoing:
                sweep_real<SplitCriterion::twoing>(f, e, count, counts, dtotal, h_parent,
                                                   static_cast<double>(min_leaf), best);
                break;
        }
        // A Gini split into two pure children cannot be beaten (ties keep the
        // first), so the remaining predictors need no sweep.
        if (opt.criterion == SplitCriterion::gdi && best.score >= dtotal) break;
    }
    return best;
}

}  // namespace rollsense::bagged_trees
