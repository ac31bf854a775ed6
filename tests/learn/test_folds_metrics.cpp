#include <catch2/catch.hpp>

#include <map>
#include <set>

#include "analysis/learn/folds.hpp"
#include "analysis/learn/metrics.hpp"
#include "analysis/learn/paper_analysis.hpp"

using namespace rollsense;
using namespace rollsense::learn;

TEST_CASE("stratified folds: balanced per class, seeded, every row once", "[learn][folds]") {
    std::vector<int> labels;
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 10 + 7 * c; ++i) labels.push_back(c);  // 10, 17, 24 rows
    auto f = stratified_folds(labels, 5, 42);
    REQUIRE(f.ok());
    std::map<int, std::map<int, int>> per_class;  // class -> fold -> count
    std::map<int, int> sizes;
    for (std::size_t i = 0; i < labels.size(); ++i) {
        REQUIRE((*f)[i] >= 0);
        REQUIRE((*f)[i] < 5);
        ++per_class[labels[i]][(*f)[i]];
        ++sizes[(*f)[i]];
    }
    for (auto& [c, folds] : per_class) {
        int lo = 1 << 30, hi = 0;
        for (int k = 0; k < 5; ++k) {
            lo = std::min(lo, folds[k]);
            hi = std::max(hi, folds[k]);
        }
        CHECK(hi - lo <= 1);
    }
    int lo = 1 << 30, hi = 0;
    for (auto& [k, n] : sizes) {
        lo = std::min(lo, n);
        hi = std::max(hi, n);
    }
    CHECK(hi - lo <= 1);
    CHECK(*stratified_folds(labels, 5, 42) == *f);
    CHECK(*stratified_folds(labels, 5, 43) != *f);
    CHECK_FALSE(stratified_folds(labels, 1, 1).ok());
    CHECK_THAT(stratified_folds(std::vector<int>{0, 1}, 5, 1).error().message, Catch::Contains("at least 5 trials; there are 2 (fewer folds, or more trials)"));
}

TEST_CASE("grouped folds keep a group together", "[learn][folds]") {
    std::vector<std::string> groups;
    std::vector<int> labels;
    for (int g = 0; g < 12; ++g)
        for (int i = 0; i < 3 + g % 4; ++i) {
            groups.push_back("session" + std::to_string(g));
            labels.push_back(i % 2);
        }
    auto f = grouped_folds(groups, labels, 4, 1);
    REQUIRE(f.ok());
    std::map<std::string, std::set<int>> folds_of;
    for (std::size_t i = 0; i < groups.size(); ++i) folds_of[groups[i]].insert((*f)[i]);
    for (auto& [g, s] : folds_of) CHECK(s.size() == 1);
    CHECK_THAT(grouped_folds(groups, labels, 13, 1).error().message, Catch::Contains("at least 13 groups; there are 12"));
    CHECK_FALSE(grouped_folds(groups, std::vector<int>{0, 1}, 4, 1).ok());
}

TEST_CASE("grouped folds are stratified as far as whole groups allow", "[learn][folds]") {
    // Blocks of one class each (the blocked CV of a mount per object): 9
    // classes x 15 blocks of 10 rows into 5 folds. Dealt by size alone, a fold
    // can get 5 of a class's blocks and another 1; stratified, every fold holds
    // 3 blocks of every class, whatever the seed.
    std::vector<std::string> groups;
    std::vector<int> labels;
    for (int c = 0; c < 9; ++c)
        for (int b = 0; b < 15; ++b)
            for (int i = 0; i < 10; ++i) {
                groups.push_back("c" + std::to_string(c) + "-b" + std::to_string(b));
                labels.push_back(c);
            }
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        auto f = grouped_folds(groups, labels, 5, seed);
        REQUIRE(f.ok());
        std::map<std::pair<int, int>, int> rows;  // (fold, class) → rows
        for (std::size_t i = 0; i < labels.size(); ++i) ++rows[{(*f)[i], labels[i]}];
        for (int fold = 0; fold < 5; ++fold)
            for (int c = 0; c < 9; ++c) CHECK(rows[{fold, c}] == 30);
    }
    // Mixed groups (leave one speed out): every group holds every class; one group per fold.
    std::vector<std::string> speeds;
    std::vector<int> classes;
    for (int s = 0; s < 3; ++s)
        for (int c = 0; c < 9; ++c)
            for (int i = 0; i < 5 + s; ++i) {
                speeds.push_back("v" + std::to_string(s));
                classes.push_back(c);
            }
    auto by_speed = grouped_folds(speeds, classes, 3, 7);
    REQUIRE(by_speed.ok());
    std::map<int, std::set<std::string>> in_fold;
    for (std::size_t i = 0; i < speeds.size(); ++i) in_fold[(*by_speed)[i]].insert(speeds[i]);
    REQUIRE(in_fold.size() == 3);
    for (auto& [fold, names] : in_fold) CHECK(names.size() == 1);
}

TEST_CASE("confusion matrix, true-positive rates, Wilson interval", "[learn][metrics]") {
    const std::vector<int> truth = {0, 0, 0, 1, 1, 2};
    const std::vector<int> pred = {0, 0, 1, 1, 1, 0};
    const auto m = confusion(truth, pred, {"A", "B", "C"});
    CHECK(m.total() == 6);
    CHECK(m.correct() == 4);
    CHECK(m.at(0, 1) == 1);
    CHECK(m.at(2, 0) == 1);
    const auto tpr = m.true_positive_rates();
    CHECK(tpr[0] == Approx(2.0 / 3));
    CHECK(tpr[1] == Approx(1.0));
    CHECK(tpr[2] == Approx(0.0));
    // Wilson for 1053 of 1164 (the paper's 90.5 %): about ±1.7 points (classifier.md §7).
    const auto w = wilson_interval(1053, 1164);
    CHECK(w.low == Approx(0.8864).margin(5e-4));
    CHECK(w.high == Approx(0.9202).margin(5e-4));
    // Hand-computed: 8 of 10, z = 1.96 → [0.4902, 0.9433].
    const auto w2 = wilson_interval(8, 10);
    CHECK(w2.low == Approx(0.4902).margin(1e-4));
    CHECK(w2.high == Approx(0.9433).margin(1e-4));
    CHECK(standard_deviation(std::vector<double>{1, 2, 3, 4}) == Approx(1.2909944));
}

TEST_CASE("the paper's analyses on a hand-made outcome", "[learn][paper]") {
    using features::FeatureRow;
    std::vector<FeatureRow> rows;
    auto add = [&](const std::string& obj, bool clean) {
        FeatureRow r;
        r.object = obj;
        r.clean = clean;
        rows.push_back(r);
    };
    const std::vector<std::string> classes = {"C1", "H1", "H2", "P1", "P2"};
    // truth / predicted pairs for clean rows:
    // C1→C1, C1→H1 (cylinder wrong), H1→P1 (hexagon called pentagon, same edge),
    // H2→C1 (hexagon → cylinder: family wrong, edge wrong), P2→H2 (pentagon called hexagon, same edge), P1→P1.
    const std::vector<std::pair<int, int>> outcome = {{0, 0}, {0, 1}, {1, 3}, {2, 0}, {4, 2}, {3, 3}};
    std::vector<int> truth, pred;
    std::vector<std::size_t> index;
    for (auto [t, p] : outcome) {
        index.push_back(rows.size());
        add(classes[static_cast<std::size_t>(t)], true);
        truth.push_back(t);
        pred.push_back(p);
    }
    add("P1", false);
    add("X9", false);
    const auto a = analyse_like_paper(rows, index, truth, pred, classes);
    CHECK(a.clean.k == 6);
    CHECK(a.clean.n == 8);
    CHECK(a.cylinders_clean.k == 2);
    CHECK(a.polygons_clean.k == 4);
    CHECK(a.polygons_clean.n == 5);
    CHECK(a.accuracy.k == 2);
    CHECK(a.family_correct.k == 4);  // C1→H1 and H2→C1 cross the family line
    CHECK(a.cylinders_misclassified.k == 1);
    CHECK(a.cylinders_misclassified.n == 2);
    CHECK(a.polygon_edge_correct.k == 3);  // H1→P1, P2→H2, P1→P1
    CHECK(a.polygon_edge_correct.n == 4);
    CHECK(a.hexagons_misclassified.k == 2);
    CHECK(a.hexagons_called_pentagons.k == 1);
    CHECK(a.pentagons_misclassified.k == 1);
    CHECK(a.pentagons_called_hexagons.k == 1);
    CHECK(a.unknown_objects == std::vector<std::string>{"X9"});
    const auto text = format_paper_comparison(a);
    CHECK_THAT(text, Catch::Contains("679 / 714 (95.1 %)"));
    CHECK_THAT(text, Catch::Contains("3 / 4 (75.0 %)"));
}
