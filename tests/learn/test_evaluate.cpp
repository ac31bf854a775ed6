// Cross-validation, evaluation report and final model with real bagged trees
// made through a factory, as the kernel does with plugins.
#include <catch2/catch.hpp>

#include <cmath>

#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/folds.hpp"
#include "learn_fixtures.hpp"

using namespace rollsense;
using namespace rollsense::learn;
using features::FeatureRow;
using namespace rollsense::learn::fixtures;


TEST_CASE("cross_validate predicts every row out of fold", "[learn][cv]") {
    const auto rows = synthetic_rows(20, 0.05, 1);
    const auto table = features::to_feature_table(rows);
    auto folds = stratified_folds(table.y, 5, 1);
    int made = 0;
    ParamSet p;
    p.set("learners", std::int64_t{10});
    auto cv = cross_validate(table, *folds, 5, bagged_trees_factory(&made), p);
    REQUIRE(cv.ok());
    CHECK(made == 5);
    CHECK(cv->fold_accuracy.size() == 5);
    for (int label : cv->predicted) CHECK(label >= 0);
    CHECK(cv->accuracy() > 0.95);  // well separated classes
}

TEST_CASE("repeated_cv on several threads gives the serial result", "[learn][cv]") {
    const auto rows = synthetic_rows(12, 0.6, 3);  // overlapping: some rows misclassified
    const auto table = features::to_feature_table(rows);
    auto plan = make_fold_plan(table.y, nullptr, 5, 6, 7);
    REQUIRE(plan.ok());
    ParamSet p;
    p.set("learners", std::int64_t{12});
    auto serial = repeated_cv(table, bagged_trees_factory(), p, *plan, 1);
    auto parallel = repeated_cv(table, bagged_trees_factory(), p, *plan, 3);
    REQUIRE(serial.ok());
    REQUIRE(parallel.ok());
    CHECK(serial->correct < serial->total);
    CHECK(parallel->repeat_accuracy == serial->repeat_accuracy);
    CHECK(parallel->fold_accuracy == serial->fold_accuracy);
    CHECK(parallel->first_predicted == serial->first_predicted);
    CHECK(parallel->first_scores == serial->first_scores);
    CHECK(parallel->confusion.correct() == serial->confusion.correct());
    CHECK(parallel->mean == serial->mean);

    // A failing repetition is reported once, naming the first that failed.
    const ClassifierFactory failing = [](const ParamSet&) -> Result<ClassifierPtr> {
        return Error{ErrorCode::plugin_error, "no classifier today"};
    };
    auto failed = repeated_cv(table, failing, p, *plan, 3);
    REQUIRE_FALSE(failed.ok());
    CHECK_THAT(failed.error().message, Catch::Contains("repetition 1") && Catch::Contains("no classifier today"));
}

// Evaluation review: the interval took the R x trials pooled predictions as
// independent cases, so ten repetitions narrowed it sqrt(10)-fold; they predict
// the same trials again. It is the pooled rate's interval over the trials.
TEST_CASE("repeated CV's Wilson interval counts the trials, not the repetitions' predictions", "[learn][cv]") {
    const auto rows = synthetic_rows(12, 0.6, 3);
    const auto table = features::to_feature_table(rows);
    ParamSet p;
    p.set("learners", std::int64_t{12});
    auto plan = make_fold_plan(table.y, nullptr, 5, 10, 7);
    REQUIRE(plan.ok());
    auto cv = repeated_cv(table, bagged_trees_factory(), p, *plan, 1);
    REQUIRE(cv.ok());
    REQUIRE(cv->total == 10 * table.rows);
    const double rate = static_cast<double>(cv->correct) / static_cast<double>(cv->total);
    const auto over_trials = wilson_interval_of_rate(rate, table.rows);
    CHECK(cv->wilson.low == Approx(over_trials.low));
    CHECK(cv->wilson.high == Approx(over_trials.high));
    const auto over_predictions = wilson_interval(cv->correct, cv->total);  // what it was
    CHECK(cv->wilson.high - cv->wilson.low > 2.5 * (over_predictions.high - over_predictions.low));
}

TEST_CASE("evaluate: repeated CV, confusion, paper analyses, reproducible", "[learn][evaluate]") {
    const auto rows = synthetic_rows(15, 0.6, 2);  // overlapping: accuracy well below 1
    EvaluationOptions o;
    o.repeats = 3;
    o.params.set("learners", std::int64_t{15});
    o.params.set("threads", std::int64_t{2});
    auto r = evaluate(rows, bagged_trees_factory(), o);
    REQUIRE(r.ok());
    CHECK(r->trials == rows.size());
    CHECK(r->clean < rows.size());
    CHECK(r->baseline.repeat_accuracy.size() == 3);
    CHECK(r->baseline.fold_accuracy.size() == 15);
    CHECK(r->baseline.total == 3 * r->clean);
    CHECK(r->baseline.mean > 0.2);
    CHECK(r->baseline.mean < 0.98);
    CHECK(r->baseline.wilson.low < r->baseline.mean);
    CHECK(r->baseline.wilson.high > r->baseline.mean);
    CHECK(r->analysis.clean.n == rows.size());
    CHECK(r->analysis.cylinders_clean.k == 45);
    CHECK(r->analysis.accuracy.n == r->clean);
    CHECK_FALSE(r->tuned.has_value());
    const std::string text = format_report(*r);
    CHECK_THAT(text, Catch::Contains("repeated stratified 5-fold") && Catch::Contains("Wilson") &&
                         Catch::Contains("paper"));
    auto again = evaluate(rows, bagged_trees_factory(), o);
    CHECK(again->baseline.repeat_accuracy == r->baseline.repeat_accuracy);
}

TEST_CASE("evaluate with optimisation: same-folds figure and nested CV beside it", "[learn][evaluate]") {
    const auto rows = synthetic_rows(10, 0.5, 3);
    EvaluationOptions o;
    o.repeats = 1;
    o.folds = 3;
    o.optimize = true;
    o.bayes.evaluations = 5;
    o.bayes.seed_points = 3;
    o.bayes.candidates = 200;
    // A small, cheap search space (the real one goes to 500 learners).
    o.space = {{"learners", SearchDimension::Scale::integer_log, 3, 12, {}},
               {"min_leaf_size", SearchDimension::Scale::integer_log, 1, 10, {}}};
    auto r = evaluate(rows, bagged_trees_factory(), o);
    REQUIRE(r.ok());
    REQUIRE(r->tuned.has_value());
    REQUIRE(r->nested.has_value());
    CHECK(r->tuned->search.history.size() == 5);
    // The reported same-folds figure is the best visited point's own CV score.
    CHECK(r->tuned->same_folds_accuracy == Approx(1.0 - r->tuned->search.best_objective()));
    CHECK(r->nested->outer_accuracy.size() == 3);
    CHECK(r->nested->chosen.size() == 3);
    CHECK(r->nested->total == r->clean);
    const std::string text = format_report(*r);
    CHECK_THAT(text, Catch::Contains("optimistic") && Catch::Contains("nested CV"));
    // Evaluation review: both spreads read "(sd)", one over repetitions, the other over outer folds.
    CHECK_THAT(text, Catch::Contains("(sd over the outer folds)"));
    // With --trials all the evaluated trials are not the clean ones: the row says which it counts.
    CHECK_THAT(text, Catch::Contains("accuracy (correct / evaluated trials)"));
}

TEST_CASE("fit_final trains on every clean trial and predicts", "[learn][train]") {
    const auto rows = synthetic_rows(12, 0.05, 4);
    EvaluationOptions o;
    o.params.set("learners", std::int64_t{8});
    auto m = fit_final(rows, bagged_trees_factory(), o);
    REQUIRE(m.ok());
    CHECK(m->classifier->class_names().size() == 9);
    auto p = m->classifier->predict(rows[0].values);
    REQUIRE(p.ok());
    CHECK(p->class_name == "C1");
}

TEST_CASE("factory and data errors surface with context", "[learn][evaluate]") {
    EvaluationOptions o;
    o.repeats = 1;
    CHECK_THAT(evaluate({}, bagged_trees_factory(), o).error().message, Catch::Contains("no clean trials"));
    const auto rows = synthetic_rows(6, 0.1, 5);
    o.params.set("learners", std::int64_t{0});
    auto r = evaluate(rows, bagged_trees_factory(), o);
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error().message, Catch::Contains("learners") && Catch::Contains("fold 1"));
}

TEST_CASE("optimisation of a classifier that declares no search space fails naming it", "[learn][evaluate]") {
    // The bagged-trees core behind a Classifier that keeps the SDK's default
    // (empty) search_space.
    struct Untunable final : Classifier {
        bagged_trees::BaggedTrees inner;
        Status train(const FeatureTable& t) override { return inner.train(t); }
        Result<Prediction> predict(std::span<const double> f) const override { return inner.predict(f); }
        std::vector<std::string> class_names() const override { return inner.class_names(); }
        Status save(const std::filesystem::path& f) const override { return inner.save(f); }
        Status load(const std::filesystem::path& f) override { return inner.load(f); }
    };
    const ClassifierFactory factory = [](const ParamSet&) -> Result<ClassifierPtr> {
        return ClassifierPtr(std::make_shared<Untunable>());
    };
    const auto rows = synthetic_rows(6, 0.1, 6);
    EvaluationOptions o;
    o.repeats = 1;
    o.folds = 3;
    o.classifier = "untunable";
    REQUIRE(evaluate(rows, factory, o).ok());  // without tuning it is fine
    o.optimize = true;
    auto r = evaluate(rows, factory, o);
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error().message, Catch::Contains("'untunable'") && Catch::Contains("no hyperparameters"));
    auto m = fit_final(rows, factory, o);
    REQUIRE_FALSE(m.ok());
    CHECK_THAT(m.error().message, Catch::Contains("'untunable'"));
}
