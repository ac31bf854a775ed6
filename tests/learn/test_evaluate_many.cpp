// Several classifiers on the same folds, the paired comparison, the text
// layout, and evaluation.json read back and checked against the evaluation.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <set>

#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/evaluation_json.hpp"
#include "analysis/learn/json_writer.hpp"
#include "analysis/learn/pipeline.hpp"
#include "json_reader.hpp"
#include "learn_fixtures.hpp"

using namespace rollsense;
using namespace rollsense::learn;
using namespace rollsense::learn::fixtures;
using rollsense::testing::Json;
using rollsense::testing::JsonReader;

namespace {

ParamSet trees(std::int64_t learners) {
    ParamSet p;
    p.set("learners", learners);
    p.set("threads", std::int64_t{2});
    return p;
}

EvaluationOptions small_options() {
    EvaluationOptions o;
    o.folds = 4;
    o.repeats = 3;
    o.seed = 5;
    return o;
}

}  // namespace

TEST_CASE("two classifiers are scored on identical folds, visible in evaluation.json", "[learn][many][json]") {
    const auto rows = synthetic_rows(14, 0.7, 3);
    const std::vector<ClassifierRequest> requests = {{"few trees", bagged_trees_factory(), trees(3)},
                                                     {"more trees", bagged_trees_factory(), trees(20)}};
    auto ev = evaluate_features(rows, requests, small_options());
    REQUIRE(ev.ok());
    REQUIRE(ev->classifiers.size() == 2);
    REQUIRE(ev->paired.size() == 1);
    CHECK(ev->plan.repeats() == 3);
    CHECK(ev->plan.seeds == std::vector<std::uint64_t>{5, 6, 7});
    CHECK(ev->refused.size() == rows.size() - ev->clean);

    const Json j = JsonReader::parse(evaluation_json(*ev));
    CHECK(j["format"].str() == "rollsense-evaluation");
    CHECK(j["version"].num() == kEvaluationJsonVersion);
    const auto& assignment = j["folds"]["assignment"];
    REQUIRE(assignment.arr().size() == 3);
    const auto& ids = j["folds"]["trials"];
    REQUIRE(ids.arr().size() == ev->clean);
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t i = 0; i < ev->clean; ++i) CHECK(assignment[r][i].num() == ev->plan.assignment[r][i]);
    // Each classifier's out-of-fold predictions name the fold their trial was
    // tested in: the same trial, the same fold, for both classifiers.
    const auto& a = j["classifiers"][0]["first_repeat_predictions"];
    const auto& b = j["classifiers"][1]["first_repeat_predictions"];
    REQUIRE(a.arr().size() == ev->clean);
    REQUIRE(b.arr().size() == ev->clean);
    for (std::size_t i = 0; i < ev->clean; ++i) {
        CHECK(a[i]["trial"].str() == ids[i].str());
        CHECK(b[i]["trial"].str() == ids[i].str());
        CHECK(a[i]["fold"].num() == b[i]["fold"].num());
        CHECK(a[i]["fold"].num() == assignment[0][i].num());
    }
    // The paired differences are the per-fold accuracies' differences.
    const auto& d = j["paired_differences"][0];
    CHECK(d["a"].str() == "few trees");
    CHECK(d["b"].str() == "more trees");
    const auto& fa = ev->classifiers[0].baseline.fold_accuracy;
    const auto& fb = ev->classifiers[1].baseline.fold_accuracy;
    REQUIRE(d["per_fold"].arr().size() == fa.size());
    for (std::size_t i = 0; i < fa.size(); ++i) CHECK(d["per_fold"][i].num() == fa[i] - fb[i]);
    CHECK(d["n"].num() == 12);
    CHECK(d["df"].num() == 11);
}

TEST_CASE("evaluation.json round-trips the evaluation's figures exactly", "[learn][json]") {
    const auto rows = synthetic_rows(12, 0.8, 4);
    auto ev = evaluate_features(rows, {{"bagged_trees:learners=5", bagged_trees_factory(), trees(5)}},
                                small_options());
    REQUIRE(ev.ok());
    const auto& c = ev->primary();
    const Json j = JsonReader::parse(evaluation_json(*ev));
    const auto& jc = j["classifiers"][0];
    CHECK(jc["name"].str() == "bagged_trees:learners=5");
    CHECK(jc["parameters"]["learners"].num() == 5);
    CHECK(jc["accuracy"]["mean"].num() == c.baseline.mean);  // exact: to_chars → from_chars
    CHECK(jc["accuracy"]["sd"].num() == c.baseline.sd);
    REQUIRE(jc["accuracy"]["per_fold"].arr().size() == 3);
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t f = 0; f < 4; ++f)
            CHECK(jc["accuracy"]["per_fold"][r][f].num() == c.baseline.fold_accuracy[r * 4 + f]);
    REQUIRE(jc["classes"].arr().size() == c.classes.size());
    const auto tpr = c.baseline.confusion.true_positive_rates();
    for (std::size_t i = 0; i < c.classes.size(); ++i) {
        CHECK(jc["classes"][i].str() == c.classes[i]);
        CHECK(jc["per_class_accuracy"][i].num() == tpr[i]);
        for (std::size_t k = 0; k < c.classes.size(); ++k)
            CHECK(jc["confusion"][i][k].num() == static_cast<double>(c.baseline.confusion.at(i, k)));
    }
    // Used and refused trials partition the rows; refused ones keep their reason.
    std::set<std::string> seen;
    for (const auto& t : jc["trials_used"].arr()) seen.insert(t.str());
    for (const auto& t : jc["trials_refused"].arr()) {
        CHECK_FALSE(t["reason"].str().empty());
        seen.insert(t["trial"].str());
    }
    CHECK(seen.size() == rows.size());
    CHECK(jc["trials_refused"].arr().size() == rows.size() - ev->clean);
    // Out-of-fold predictions of the first repeat, with scores summing to 1.
    const auto& p = jc["first_repeat_predictions"];
    for (std::size_t i = 0; i < ev->clean; ++i) {
        CHECK(p[i]["true"].str() == c.classes[static_cast<std::size_t>(ev->truth[i])]);
        CHECK(p[i]["predicted"].str() == c.classes[static_cast<std::size_t>(c.baseline.first_predicted[i])]);
        double sum = 0;
        for (std::size_t k = 0; k < c.classes.size(); ++k) {
            CHECK(p[i]["scores"][k].num() == c.baseline.first_scores[i][k]);
            sum += p[i]["scores"][k].num();
        }
        CHECK(sum == Approx(1.0));
    }
    CHECK(j["paired_differences"].arr().empty());
}

TEST_CASE("the same classifier twice: paired difference exactly 0", "[learn][many]") {
    const auto rows = synthetic_rows(12, 0.8, 6);
    auto ev = evaluate_features(rows,
                                {{"a", bagged_trees_factory(), trees(7)}, {"b", bagged_trees_factory(), trees(7)}},
                                small_options());
    REQUIRE(ev.ok());
    const auto& d = ev->paired.at(0).difference;
    CHECK(d.n() == 12);
    CHECK(d.mean == 0.0);
    CHECK(d.sd == 0.0);
    CHECK(d.t == 0.0);
    CHECK(d.t_corrected == 0.0);
    CHECK(d.ties == 12);
    CHECK(ev->classifiers[0].baseline.mean == ev->classifiers[1].baseline.mean);
    const std::string text = format_evaluation(*ev);
    CHECK_THAT(text, Catch::Contains("2 classifiers on the same 3 x stratified 4-fold partitions (seeds 5..7)"));
    CHECK_THAT(text, Catch::Contains("a − b: mean +0.00 points, sd 0.00, n 12, t 0.00, t corrected 0.00"));
    CHECK_THAT(text, Catch::Contains("==== a ====") && Catch::Contains("==== b ===="));
}

TEST_CASE("one classifier: evaluation.txt as format_report always printed it", "[learn][many]") {
    const auto rows = synthetic_rows(10, 0.8, 7);
    auto ev = evaluate_features(rows, {{"x", bagged_trees_factory(), trees(4)}}, small_options());
    REQUIRE(ev.ok());
    CHECK(format_evaluation(*ev) == format_report(ev->primary()));
    CHECK(ev->paired.empty());
    CHECK(ev->primary().seconds == ev->seconds);
}

TEST_CASE("paired differences: sign counts and the two t statistics", "[learn][metrics]") {
    const std::vector<double> a = {0.8, 0.7, 0.9, 0.6}, b = {0.7, 0.7, 0.8, 0.5};
    const auto d = paired_difference(a, b, 1.0 / 3.0);
    CHECK(d.a_better == 3);
    CHECK(d.ties == 1);
    CHECK(d.b_better == 0);
    CHECK(d.mean == Approx(0.075));
    CHECK(d.sd == Approx(0.05));
    CHECK(d.t == Approx(0.075 / (0.05 / 2.0)));
    CHECK(d.t_corrected == Approx(0.075 / std::sqrt((0.25 + 1.0 / 3.0) * 0.0025)));
    CHECK(d.t_corrected < d.t);
    // Constant non-zero difference: no spread, infinite t (written as null in JSON).
    const auto c = paired_difference(std::vector<double>{0.5, 0.6}, std::vector<double>{0.4, 0.5}, 0.25);
    CHECK(std::isinf(c.t));
}

TEST_CASE("classifier lists: names, per-entry parameters, errors", "[learn][many]") {
    ParamSet common;
    common.set("threads", std::int64_t{1});
    auto specs = parse_classifier_list("bagged_trees,bagged_trees:learners=10:min_leaf=2,bagged_trees", common);
    REQUIRE(specs.ok());
    REQUIRE(specs->size() == 3);
    CHECK((*specs)[0].name == "bagged_trees");
    CHECK((*specs)[1].name == "bagged_trees:learners=10:min_leaf=2");
    CHECK((*specs)[1].plugin == "bagged_trees");
    CHECK(std::get<std::int64_t>((*specs)[1].params.values().at("learners")) == 10);
    CHECK(std::get<std::int64_t>((*specs)[1].params.values().at("threads")) == 1);
    CHECK((*specs)[2].name == "bagged_trees #2");
    CHECK_THAT(parse_classifier_list("a,,b").error().message, Catch::Contains("empty entry"));
    CHECK_THAT(parse_classifier_list("a:learners").error().message,
               Catch::Contains("'a:learners'") && Catch::Contains("not key=value"));
    CHECK_THAT(parse_classifier_list(":x=1").error().message, Catch::Contains("no plugin name"));
}

TEST_CASE("the input step: features from rows alone, series only from a dataset folder", "[learn][many]") {
    const auto rows = synthetic_rows(3, 0.1, 1);
    auto t = make_input_tables(rows, {}, {ClassifierInput::series}, {});
    REQUIRE_FALSE(t.ok());
    CHECK(t.error().code == ErrorCode::invalid_argument);
    CHECK_THAT(t.error().message, Catch::Contains("not a dataset folder"));
    auto f = make_input_tables(rows, {}, {ClassifierInput::features}, {});
    REQUIRE(f.ok());
    REQUIRE(f->kinds == std::vector<std::string>{"features"});
    CHECK(f->tables.front().rows == f->row_of.size());
    CHECK(f->selection == "paper_clean");
}

TEST_CASE("JsonWriter: escapes, round-trip numbers, null for non-finite, misuse throws", "[learn][json]") {
    JsonWriter w;
    const double third = 1.0 / 3.0, tiny = 4.9406564584124654e-324, big = 1.7976931348623157e308;
    w.begin_object()
        .key("text")
        .value("quote \" backslash \\ newline \n tab \t bell \x07 µ")
        .key("numbers")
        .begin_array()
        .value(third)
        .value(0.1)
        .value(tiny)
        .value(big)
        .value(-0.0)
        .value(std::int64_t{-9007199254740993})
        .end_array()
        .key("nan")
        .value(std::numeric_limits<double>::quiet_NaN())
        .key("inf")
        .value(std::numeric_limits<double>::infinity())
        .key("empty")
        .begin_object()
        .end_object()
        .key("nested")
        .begin_array()
        .begin_object()
        .key("x")
        .value(true)
        .end_object()
        .end_array()
        .end_object();
    REQUIRE(w.complete());
    const Json j = JsonReader::parse(w.str());
    CHECK(j["text"].str() == "quote \" backslash \\ newline \n tab \t bell \x07 µ");
    CHECK(j["numbers"][0].num() == third);
    CHECK(j["numbers"][1].num() == 0.1);
    CHECK(j["numbers"][2].num() == tiny);
    CHECK(j["numbers"][3].num() == big);
    CHECK(j["nan"].is_null());
    CHECK(j["inf"].is_null());
    CHECK(j["empty"].obj().empty());
    CHECK(j["nested"][0]["x"].boolean());
    CHECK_THAT(w.str(), Catch::Contains("\"numbers\": [0.3333333333333333, 0.1,"));
    CHECK_THAT(w.str(), Catch::Contains("-9007199254740993"));

    JsonWriter bad;
    bad.begin_object();
    CHECK_THROWS(bad.value(1.0));  // no key
    JsonWriter bad2;
    bad2.begin_array();
    CHECK_THROWS(bad2.key("x"));
    CHECK_THROWS(bad2.end_object());
}

// Review finding (live view): bytes that are not UTF-8 (a script's rs.status,
// a device's error message) went into the JSON as they were, and a JSON text
// must be UTF-8. Each maximal ill-formed subpart becomes one U+FFFD.
TEST_CASE("json_quote: well-formed UTF-8 passes, ill-formed bytes become U+FFFD", "[learn][json]") {
    const std::string fffd = "\xEF\xBF\xBD";
    CHECK(json_quote("µ € 𝄞 ascii") == "\"µ € 𝄞 ascii\"");
    CHECK(json_quote("a\xff\xfe") == "\"a" + fffd + fffd + "\"");
    CHECK(json_quote("lab\xc3(") == "\"lab" + fffd + "(\"");                  // a lead byte without its trail
    CHECK(json_quote("\xe2\x82") == "\"" + fffd + "\"");                      // truncated at the end: one U+FFFD
    CHECK(json_quote("\xc0\xaf") == "\"" + fffd + fffd + "\"");               // overlong '/'
    CHECK(json_quote("\xed\xa0\x80") == "\"" + fffd + fffd + fffd + "\"");    // a surrogate
    CHECK(json_quote("\xf4\x90\x80\x80") == "\"" + fffd + fffd + fffd + fffd + "\"");  // above U+10FFFF
    CHECK(json_quote("\xf0\x9f\x98") == "\"" + fffd + "\"");                  // 3 of 4 bytes
    CHECK(json_quote("\x80x\"") == "\"" + fffd + "x\\\"\"");                  // a stray trail byte, then escapes
    const Json j = JsonReader::parse("{\"s\":" + json_quote("ok \xff µ") + "}");
    CHECK(j["s"].str() == "ok " + fffd + " µ");
}
