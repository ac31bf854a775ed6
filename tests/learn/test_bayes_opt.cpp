#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "analysis/learn/bayes_opt.hpp"
#include "rollsense/bagged_trees/bagged_trees.hpp"

using namespace rollsense;
using namespace rollsense::learn;
using Scale = SearchDimension::Scale;

namespace {

// A smooth bowl over a log-integer, a linear integer and a categorical
// dimension, minimum 0 at learners = 100, depth = 7, kind = "b".
double bowl(const ParamSet& p) {
    const double a = std::log(static_cast<double>(p.get_int("learners")) / 100.0);
    const double b = (static_cast<double>(p.get_int("depth")) - 7.0) / 10.0;
    const double c = p.get_string("kind") == "b" ? 0.0 : 0.3;
    return a * a + b * b + c;
}

SearchSpace space() {
    return {{"learners", Scale::integer_log, 10, 1000, {}},
            {"depth", Scale::integer_linear, 1, 20, {}},
            {"kind", Scale::categorical, 0, 0, {"a", "b", "c"}}};
}

}  // namespace

TEST_CASE("Bayesian optimisation finds the bowl's minimum in 30 evaluations", "[learn][bayesopt]") {
    BayesOptOptions o;
    o.evaluations = 30;
    o.seed = 3;
    int calls = 0;
    ParamSet fixed;
    fixed.set("seed", std::int64_t{9});
    auto r = bayes_optimize(
        space(),
        [&](const ParamSet& p) -> Result<double> {
            ++calls;
            CHECK(p.get_int("seed") == 9);  // fixed parameters travel with every evaluation
            return bowl(p);
        },
        fixed, o);
    REQUIRE(r.ok());
    CHECK(calls == 30);
    CHECK(r->history.size() == 30);
    CHECK(r->best_params().get_string("kind") == "b");
    CHECK(r->best_objective() < 0.02);  // within ~13 % of 100 learners and ±1 of depth 7
    // Random search with the same budget is not as good on average: the seed
    // points alone (4 random draws) are worse than the final answer.
    double best_seed = 1e9;
    for (int i = 0; i < 4; ++i) best_seed = std::min(best_seed, r->history[static_cast<std::size_t>(i)].objective);
    CHECK(r->best_objective() < best_seed);
}

TEST_CASE("Bayesian optimisation is reproducible and reports objective errors", "[learn][bayesopt]") {
    BayesOptOptions o;
    o.evaluations = 8;
    auto f = [](const ParamSet& p) -> Result<double> { return bowl(p); };
    auto a = bayes_optimize(space(), f, {}, o);
    auto b = bayes_optimize(space(), f, {}, o);
    REQUIRE(a.ok());
    for (std::size_t i = 0; i < a->history.size(); ++i)
        CHECK(a->history[i].objective == b->history[i].objective);
    auto failing = bayes_optimize(
        space(), [](const ParamSet&) -> Result<double> { return Error{ErrorCode::invalid_argument, "boom"}; }, {}, o);
    REQUIRE_FALSE(failing.ok());
    CHECK_THAT(failing.error().message, Catch::Contains("evaluation 1") && Catch::Contains("boom"));
    SearchSpace bad = {{"x", Scale::integer_log, 0, 10, {}}};
    CHECK_FALSE(bayes_optimize(bad, f, {}, o).ok());
}

TEST_CASE("the bagged-trees plugin declares classifier.md §3's search space", "[learn][bayesopt]") {
    const bagged_trees::BaggedTrees clf;
    const auto s = clf.search_space(1164, 13);
    REQUIRE(s.size() == 5);
    CHECK(s[0].name == "learners");
    CHECK(s[0].scale == Scale::integer_log);
    CHECK(s[0].low == 10);
    CHECK(s[0].high == 500);
    CHECK(s[1].name == "min_leaf_size");
    CHECK(s[1].high == 582);
    CHECK(s[2].name == "max_num_splits");
    CHECK(s[2].high == 1163);
    CHECK(s[3].name == "predictors_per_split");
    CHECK(s[3].scale == Scale::integer_linear);
    CHECK(s[3].high == 13);
    CHECK(s[4].choices == std::vector<std::string>{"gdi", "twoing", "deviance"});
    CHECK(clf.search_space(3, 1)[1].high == 2);
    CHECK(clf.search_space(3, 1)[3].high == 2);
}

namespace {

// A classifier with nothing to tune (the SDK's default search_space).
class Untunable final : public Classifier {
public:
    Status train(const FeatureTable&) override { return {}; }
    Result<Prediction> predict(std::span<const double>) const override { return Prediction{}; }
    std::vector<std::string> class_names() const override { return {}; }
    Status save(const std::filesystem::path&) const override { return {}; }
    Status load(const std::filesystem::path&) override { return {}; }
};

ClassifierFactory factory_of(std::function<ClassifierPtr()> make, int* made) {
    return [make, made](const ParamSet&) -> Result<ClassifierPtr> {
        ++*made;
        return make();
    };
}

}  // namespace

TEST_CASE("tuning asks the classifier the factory makes for its space", "[learn][bayesopt]") {
    int made = 0;
    const auto trees = factory_of([] { return std::make_shared<bagged_trees::BaggedTrees>(); }, &made);
    auto declared = declared_search_space(trees, {}, 100, 7);
    REQUIRE(declared.ok());
    CHECK(made == 1);  // one instance, asked
    REQUIRE(declared->size() == 5);
    CHECK((*declared)[2].high == 99);
    CHECK((*declared)[3].high == 7);

    // A caller's own space wins and needs no instance.
    auto given = declared_search_space(trees, {}, 100, 7, space());
    REQUIRE(given.ok());
    CHECK(made == 1);
    CHECK(given->size() == 3);

    const auto none = factory_of([] { return std::make_shared<Untunable>(); }, &made);
    auto empty = declared_search_space(none, {}, 100, 7);
    REQUIRE(empty.ok());
    CHECK(empty->empty());  // fine when nothing is tuned
    auto refused = tuning_space(none, {}, 100, 7, {}, "untunable");
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().message, Catch::Contains("'untunable'") && Catch::Contains("no hyperparameters"));

    const ClassifierFactory broken = [](const ParamSet&) -> Result<ClassifierPtr> {
        return Error{ErrorCode::invalid_argument, "learners must be at least 1"};
    };
    auto failed = declared_search_space(broken, {}, 100, 7);
    REQUIRE_FALSE(failed.ok());
    CHECK_THAT(failed.error().message, Catch::Contains("search space") && Catch::Contains("learners must"));
}
