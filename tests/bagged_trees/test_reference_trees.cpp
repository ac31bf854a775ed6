// The tree builder is optimised (ranks instead of values, integer Gini counts,
// skipped sweeps and partitions); these tests pin that it grows exactly the
// trees the straightforward builder grew. The fingerprints were produced by
// the builder before the optimisation (commit a023d65), on data with many tied
// values, for every criterion and the options that change the sweep. If a
// change to how trees grow is intended, recompute them and say so in the
// commit; otherwise a mismatch is a bug in the builder.
#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "rollsense/bagged_trees/ensemble.hpp"
#include "toy_data.hpp"
#include "tree_hash.hpp"

using namespace rollsense;
using namespace rollsense::bagged_trees;

namespace {

struct Case {
    const char* name;
    SplitCriterion criterion;
    int min_leaf_size, predictors_per_split, max_num_splits;
    std::uint64_t ties_hash, overlapping_hash;
};

const Case cases[] = {
    {"gdi", SplitCriterion::gdi, 1, 0, 0, 0xe2c001cd520b084aull, 0x75feb7087066e4adull},
    {"gdi, min_leaf_size 3", SplitCriterion::gdi, 3, 0, 0, 0xc657c531fe6e87e7ull, 0xf2e01a1a2e16f1d0ull},
    {"gdi, ceil(sqrt(p)) predictors", SplitCriterion::gdi, 1, -1, 0, 0x9064560481718ba9ull, 0x75feb7087066e4adull},
    {"gdi, 7 splits", SplitCriterion::gdi, 1, 0, 7, 0xa43444df8e3f4fa9ull, 0xb785a0f55baffd77ull},
    {"deviance", SplitCriterion::deviance, 1, 0, 0, 0x411efb3a8f9d6a34ull, 0x8b55ad334853c3f1ull},
    {"twoing, min_leaf_size 2", SplitCriterion::twoing, 2, 0, 0, 0x0c864510707a19f9ull, 0x1130dfddb8a72661ull},
};

EnsembleOptions options_for(const Case& c, unsigned threads) {
    EnsembleOptions o;
    o.learners = 10;
    o.seed = 7;
    o.threads = threads;
    o.tree.criterion = c.criterion;
    o.tree.min_leaf_size = c.min_leaf_size;
    o.tree.predictors_per_split = c.predictors_per_split;
    o.tree.max_num_splits = c.max_num_splits;
    return o;
}

}  // namespace

TEST_CASE("the builder grows the reference trees, bit for bit", "[bagged_trees][reference]") {
    const auto ties = toy::ties(500, 21);
    const auto overlapping = toy::overlapping(400, 22);
    for (const auto& c : cases) {
        for (unsigned threads : {1u, 3u}) {
            INFO(c.name << ", " << threads << " thread(s)");
            Ensemble a, b;
            REQUIRE(a.train(ties, options_for(c, threads)).ok());
            REQUIRE(b.train(overlapping, options_for(c, threads)).ok());
            CHECK(toy::tree_hash(a) == c.ties_hash);
            CHECK(toy::tree_hash(b) == c.overlapping_hash);
        }
    }
}

TEST_CASE("a training set above 2^17 rows grows the reference trees too", "[bagged_trees][reference]") {
    // The Gini sweep forms its score's numerator and denominator in integers
    // only while the node's weight is below 2^17 (every product then stays
    // below 2^53, so they are exact); nodes above that, near the root here,
    // take the double formula. Both must grow what the builder before that
    // change grew (fingerprints from commit 97abbb4), grown out and cut short.
    const auto big = toy::ties(140000, 24);
    const std::pair<int, std::uint64_t> runs[] = {{0, 0xf72eac61aaa0f3b7ull}, {40, 0x4d99e6598e9268c5ull}};
    for (const auto& [max_num_splits, hash] : runs) {
        INFO("max_num_splits " << max_num_splits);
        EnsembleOptions o;
        o.learners = 2;
        o.seed = 5;
        o.threads = 1;
        o.tree.max_num_splits = max_num_splits;
        Ensemble m;
        REQUIRE(m.train(big, o).ok());
        CHECK(toy::tree_hash(m) == hash);
    }
}

TEST_CASE("thresholds fall halfway between distinct training values", "[bagged_trees][reference]") {
    // Features on grids: a threshold halfway between two grid values is on the
    // half grid, strictly inside the range, and never on a value itself
    // except where the node lacks the values between (e.g. 0 | 2 → 1).
    const auto data = toy::ties(500, 23);
    Ensemble m;
    REQUIRE(m.train(data, {}).ok());
    std::size_t grid_splits = 0;
    for (const auto& t : m.trees()) {
        for (std::size_t i = 0; i < t.nodes(); ++i) {
            const double th = t.threshold[i];
            switch (t.feature[i]) {
                case 1:  // 0, 0.25, …, 1
                    CHECK(th * 8.0 == std::round(th * 8.0));
                    CHECK((th > 0.0 && th < 1.0));
                    ++grid_splits;
                    break;
                case 2:  // 0, 1, 2, 3
                    CHECK(th * 2.0 == std::round(th * 2.0));
                    CHECK((th > 0.0 && th < 3.0));
                    ++grid_splits;
                    break;
                case 3:  // 0 or 1
                    CHECK(th == 0.5);
                    break;
                default: break;
            }
        }
    }
    CHECK(grid_splits > 0);
}

TEST_CASE("negative values sort below positive ones, and -0 and +0 are one value", "[bagged_trees][reference]") {
    // The presort ranks values through their bit patterns: negative numbers
    // must come out in value order below the positive ones, and -0 with +0
    // (equal values) must share a rank so that no threshold separates them.
    // Class 0 below -0.5, class 1 at 2, and the zeros half class 1 (+0) and
    // half class 2 (-0): the only thresholds are -2, -0.5 and 1, and the
    // zeros end in mixed leaves.
    auto data = toy::empty_table(1, 3);
    const double values[] = {-3.0, -1.0, -0.0, 0.0, 2.0};
    for (std::size_t r = 0; r < 400; ++r) {
        const double v = values[r % 5];
        data.x.push_back(v);
        data.y.push_back(v < -0.5 ? 0 : v > 0.0 ? 1 : std::signbit(v) ? 2 : 1);
        ++data.rows;
    }
    Ensemble m;
    REQUIRE(m.train(data, {}).ok());
    bool cut_at_minus_half = false;
    for (const auto& t : m.trees()) {
        for (std::size_t i = 0; i < t.nodes(); ++i) {
            if (t.feature[i] < 0) continue;
            const double th = t.threshold[i];
            CHECK((th == -2.0 || th == -0.5 || th == 1.0));
            cut_at_minus_half = cut_at_minus_half || th == -0.5;
        }
    }
    CHECK(cut_at_minus_half);
    std::vector<double> scores(3);
    m.predict(std::vector<double>{-0.0}, scores);
    CHECK(scores[0] == 0.0);  // the zeros' leaves hold both of their classes
    CHECK(scores[1] > 0.0);
    CHECK(scores[2] > 0.0);
}
