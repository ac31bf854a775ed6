#include <catch2/catch.hpp>

#include <numeric>

#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "toy_data.hpp"

using namespace rollsense;
using namespace rollsense::bagged_trees;

namespace {

double accuracy(const Ensemble& m, const FeatureTable& t) {
    const auto pred = m.predict_rows(t.x, t.rows);
    std::size_t ok = 0;
    for (std::size_t i = 0; i < t.rows; ++i) ok += pred[i] == t.y[i];
    return static_cast<double>(ok) / static_cast<double>(t.rows);
}

}  // namespace

TEST_CASE("separable data: every split criterion learns the rule", "[bagged_trees]") {
    const auto train = toy::separable(300, 1);
    const auto test = toy::separable(300, 2);
    for (auto crit : {SplitCriterion::gdi, SplitCriterion::deviance, SplitCriterion::twoing}) {
        INFO("criterion " << to_string(crit));
        EnsembleOptions o;
        o.tree.criterion = crit;
        Ensemble m;
        REQUIRE(m.train(train, o).ok());
        CHECK(m.trees().size() == 30);
        CHECK(accuracy(m, train) == 1.0);
        CHECK(accuracy(m, test) >= 0.97);  // only points within a bootstrap gap of 1/3, 2/3 can miss
    }
}

TEST_CASE("non-separable data: near the Bayes rate, never perfect", "[bagged_trees]") {
    const auto train = toy::overlapping(800, 3);
    const auto test = toy::overlapping(2000, 4);
    Ensemble m;
    REQUIRE(m.train(train, {}).ok());
    const double acc = accuracy(m, test);
    CHECK(acc > 0.72);  // Bayes optimum 0.841; grown-out bagged trees lose a little
    CHECK(acc < 0.86);
    CHECK(accuracy(m, train) > 0.95);  // grown-out trees nearly memorise their training set
}

TEST_CASE("posteriors are averages of leaf class fractions and sum to one", "[bagged_trees]") {
    const auto train = toy::overlapping(200, 5);
    BaggedTrees c;
    REQUIRE(c.train(train).ok());
    const std::vector<double> x = {0.1, -0.3};
    auto p = c.predict(x);
    REQUIRE(p.ok());
    CHECK(std::accumulate(p->scores.begin(), p->scores.end(), 0.0) == Approx(1.0));
    CHECK(p->scores[static_cast<std::size_t>(p->label)] ==
          *std::max_element(p->scores.begin(), p->scores.end()));
    CHECK(p->class_name == c.class_names()[static_cast<std::size_t>(p->label)]);
    // With grown-out trees each leaf is pure, so every score is a multiple of 1/30.
    for (double s : p->scores) CHECK(std::abs(s * 30 - std::round(s * 30)) < 1e-9);
}

TEST_CASE("the model is the same for any thread count, and depends on the seed", "[bagged_trees]") {
    const auto train = toy::overlapping(400, 6);
    std::string reference;
    for (unsigned threads : {1u, 2u, 3u, 7u}) {
        EnsembleOptions o;
        o.threads = threads;
        o.seed = 42;
        Ensemble m;
        REQUIRE(m.train(train, o).ok());
        auto text = m.serialize();
        text = text.substr(text.find("trees "));  // the options line records nothing thread-specific anyway
        if (reference.empty()) reference = text;
        CHECK(text == reference);
    }
    EnsembleOptions other;
    other.seed = 43;
    Ensemble m;
    REQUIRE(m.train(train, other).ok());
    auto text = m.serialize();
    CHECK(text.substr(text.find("trees ")) != reference);
}

TEST_CASE("tree options: stumps, leaf size, predictor sampling", "[bagged_trees]") {
    const auto train = toy::separable(200, 7);
    SECTION("max_num_splits = 1 grows stumps") {
        EnsembleOptions o;
        o.tree.max_num_splits = 1;
        Ensemble m;
        REQUIRE(m.train(train, o).ok());
        for (const auto& t : m.trees()) CHECK(t.nodes() == 3);
    }
    SECTION("max_num_splits = 2 on three classes: layer-wise growth") {
        EnsembleOptions o;
        o.tree.max_num_splits = 2;
        Ensemble m;
        REQUIRE(m.train(train, o).ok());
        for (const auto& t : m.trees()) CHECK(t.nodes() <= 5);
        CHECK(accuracy(m, train) > 0.95);
    }
    SECTION("a minimum leaf size larger than half the data allows no split") {
        EnsembleOptions o;
        o.tree.min_leaf_size = 150;
        Ensemble m;
        REQUIRE(m.train(train, o).ok());
        for (const auto& t : m.trees()) CHECK(t.nodes() == 1);
    }
    SECTION("one random predictor per split still finds x0 eventually") {
        EnsembleOptions o;
        o.tree.predictors_per_split = 1;
        Ensemble m;
        REQUIRE(m.train(train, o).ok());
        CHECK(accuracy(m, train) == 1.0);
    }
    SECTION("ceil(sqrt(p)) sampling") {
        EnsembleOptions o;
        o.tree.predictors_per_split = -1;
        Ensemble m;
        REQUIRE(m.train(train, o).ok());
        CHECK(accuracy(m, toy::separable(200, 8)) > 0.9);
    }
}

TEST_CASE("bad input gives errors that say what is wrong", "[bagged_trees]") {
    BaggedTrees c;
    CHECK(c.predict(std::vector<double>{1.0, 2.0}).error().code == ErrorCode::state_error);
    auto t = toy::separable(20, 9);
    t.x[4] = std::nan("");
    auto s = c.train(t);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.message(), Catch::Contains("row 1 feature 'F2'"));
    t = toy::separable(20, 9);
    REQUIRE(c.train(t).ok());
    CHECK_THAT(c.predict(std::vector<double>{1.0}).error().message, Catch::Contains("trained on 3"));
    CHECK_THAT(c.predict(std::vector<double>{1.0, std::nan(""), 0.0}).error().message, Catch::Contains("'F2'"));
    t.y[3] = 7;
    CHECK_THAT(c.train(t).message(), Catch::Contains("label 7"));
}

TEST_CASE("parameters: schema validation and configuration", "[bagged_trees]") {
    auto bad = validate_params(bagged_trees_schema(), {{"learners", std::int64_t{0}}}, "profile.lua: classifier");
    CHECK_FALSE(bad.ok());
    auto good = validate_params(bagged_trees_schema(),
                                {{"learners", std::int64_t{12}}, {"split_criterion", std::string("deviance")}},
                                "profile.lua: classifier");
    REQUIRE(good.ok());
    BaggedTrees c;
    REQUIRE(c.on_configure(*good, {}).ok());
    CHECK(c.options().learners == 12);
    CHECK(c.options().tree.criterion == SplitCriterion::deviance);
    CHECK(c.options().tree.predictors_per_split == 0);
    REQUIRE(c.train(toy::separable(50, 10)).ok());
    auto info = c.invoke("info", {});
    REQUIRE(info.ok());
    CHECK(std::get<std::int64_t>(info->at("trees")) == 12);
}
