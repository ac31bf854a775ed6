// One repetition has no spread: the sd over repetitions does not exist, so
// evaluation.json holds null (docs/evaluation-json.md) and the text says so
// instead of printing "± 0.0". With two or more repetitions nothing changes.
#include <catch2/catch.hpp>

#include <cmath>

#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/evaluation_json.hpp"
#include "json_reader.hpp"
#include "learn_fixtures.hpp"

using namespace rollsense;
using namespace rollsense::learn;
using namespace rollsense::learn::fixtures;
using rollsense::testing::JsonReader;

namespace {

Result<Evaluation> evaluate_with(int repeats, std::vector<CvScheme> schemes = {}) {
    EvaluationOptions o;
    o.folds = 3;
    o.repeats = repeats;
    o.seed = 2;
    o.schemes = std::move(schemes);
    ParamSet p;
    p.set("learners", std::int64_t{5});
    p.set("threads", std::int64_t{1});
    auto rows = synthetic_rows(9, 0.8, 3);
    for (std::size_t i = 0; i < rows.size(); ++i) rows[i].speed = std::to_string(10 * (1 + i % 3));  // three speeds
    return evaluate_features(rows, {{"a", bagged_trees_factory(), p}, {"b", bagged_trees_factory(), p}}, o);
}

}  // namespace

TEST_CASE("the sd of fewer than two values does not exist", "[learn][metrics]") {
    CHECK(std::isnan(standard_deviation(std::vector<double>{0.8})));
    CHECK(std::isnan(standard_deviation(std::vector<double>{})));
    CHECK_FALSE(has_spread(standard_deviation(std::vector<double>{0.8})));
    CHECK(has_spread(standard_deviation(std::vector<double>{0.8, 0.8})));
    CHECK(standard_deviation(std::vector<double>{0.8, 0.8}) == 0.0);
}

TEST_CASE("one repetition: sd null in evaluation.json and no ± 0.0 in the text", "[learn][json][spread]") {
    auto ev = evaluate_with(1);
    REQUIRE(ev.ok());
    const auto j = JsonReader::parse(evaluation_json(*ev));
    for (std::size_t c = 0; c < 2; ++c) {
        CHECK(j["classifiers"][c]["accuracy"]["sd"].is_null());
        CHECK(j["classifiers"][c]["accuracy"]["mean"].num() == ev->classifiers[c].baseline.mean);
    }
    // The paired differences have one value per fold: their sd exists.
    CHECK_FALSE(j["paired_differences"][std::size_t{0}]["sd"].is_null());
    const std::string text = format_evaluation(*ev);
    CHECK_THAT(text, !Catch::Contains("± 0.0"));
    CHECK_THAT(text, Catch::Contains("(one repetition: no spread)"));
    const std::string one = format_report(ev->primary());
    CHECK_THAT(one, Catch::Contains("accuracy ") && Catch::Contains("% (one repetition: no spread)   pooled"));
}

TEST_CASE("leave one group out runs once so its sd is null too", "[learn][json][spread]") {
    // Three speeds, three folds: leave one speed out, a single repetition.
    auto schemes = parse_cv_schemes("grouped", "speed", "");
    REQUIRE(schemes.ok());
    auto ev = evaluate_with(2, *schemes);
    REQUIRE(ev.ok());
    const auto j = JsonReader::parse(evaluation_json(*ev));
    const auto& c = j["classifiers"][std::size_t{0}];
    CHECK_FALSE(c["accuracy"]["sd"].is_null());  // two repetitions of random k-fold: a spread
    const auto& s = c["cv_schemes"][std::size_t{0}];
    REQUIRE(ev->primary().scheme_cv.at(0).cv.repeats == 1);
    CHECK(s["sd"].is_null());
    CHECK_THAT(format_report(ev->primary()), Catch::Contains("(one repetition: no spread)"));
}

TEST_CASE("two or more repetitions show the ± sd as before", "[learn][spread]") {
    auto ev = evaluate_with(2);
    REQUIRE(ev.ok());
    const std::string text = format_report(ev->primary());
    CHECK_THAT(text, Catch::Contains(" (sd)   pooled") && Catch::Contains(" % ± "));
    CHECK_THAT(text, !Catch::Contains("no spread"));
}
