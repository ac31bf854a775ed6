// The learning pipeline's input step with a series classifier: feature and
// series classifiers on the same trials and the same folds (checked through
// evaluation.json), the trial selections, and what the step refuses.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>

#include "json_reader.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/evaluation_json.hpp"
#include "analysis/learn/pipeline.hpp"
#include "analysis/report/report.hpp"
#include "analysis/series/series_table.hpp"
#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "rollsense/minirocket/minirocket.hpp"
#include "classifier_factory.hpp"
#include "stock_run.hpp"

using namespace rollsense;
using namespace rollsense::learn;
using rollsense::testing::Json;
using rollsense::testing::JsonReader;
using rollsense::testing::factory_of;
using rollsense::testing::stock_run;
using rollsense::testing::stock_run_dir;

namespace {

PreparedClassifier trees() {
    ParamSet p;
    p.set("learners", std::int64_t{10});
    return {{"bagged_trees", "bagged_trees", p}, factory_of<bagged_trees::BaggedTrees>(bagged_trees::bagged_trees_schema()),
            ClassifierInput::features};
}

PreparedClassifier rocket() {
    ParamSet p;
    p.set("num_features", std::int64_t{840});
    p.set("threads", std::int64_t{2});
    return {{"minirocket", "minirocket", p}, factory_of<minirocket::MiniRocket>(minirocket::minirocket_schema()),
            ClassifierInput::series};
}

EvaluationOptions small() {
    EvaluationOptions o;
    o.folds = 2;
    o.repeats = 2;
    o.seed = 3;
    return o;
}

const std::vector<features::FeatureRow>& rows() {
    static const auto r = [] {
        auto x = features::extract_dataset(stock_run(), {}, 2);
        REQUIRE(x.ok());
        return *x;
    }();
    return r;
}

// The series rule's refusals on the stock run, by trial id.
std::map<std::string, std::string> series_refusals() {
    auto t = series::series_table(stock_run(), stock_run().trials(), {"ch1", "ch2", "ch3"}, {}, 2);
    REQUIRE(t.ok());
    std::map<std::string, std::string> out;
    for (const auto& r : t->refused) out[r.trial_id] = r.reason;
    return out;
}

}  // namespace

TEST_CASE("a feature and a series classifier get the same trials and identical folds (evaluation.json)",
          "[series][pipeline][json]") {
    auto ev = evaluate_prepared(rows(), stock_run_dir(), {trees(), rocket()}, small());
    REQUIRE(ev.ok());
    const Json j = JsonReader::parse(evaluation_json(*ev));
    CHECK(j["input"].str() == "features+series");
    CHECK(j["selection"].str() == "paper_clean");
    const auto& cs = j["classifiers"].arr();
    REQUIRE(cs.size() == 2);
    CHECK(cs[0]["input"].str() == "features");
    CHECK(cs[1]["input"].str() == "series");

    // The trials: the paper's clean ones the series rule accepts too, and every other one refused with its rules.
    const auto refusals = series_refusals();
    std::set<std::string> expected;
    for (const auto& r : rows())
        if (r.clean && !refusals.count(r.trial_id)) expected.insert(r.trial_id);
    const auto& ids = j["folds"]["trials"].arr();
    std::set<std::string> used;
    for (const auto& id : ids) used.insert(id.str());
    CHECK(used == expected);
    CHECK(ids.size() + cs[0]["trials_refused"].arr().size() == rows().size());
    for (const auto& r : cs[0]["trials_refused"].arr()) {
        const std::string& why = r["reason"].str();
        const bool peak = why.find("peak rule: ") != std::string::npos;
        const bool ser = why.find("series rule: ") != std::string::npos;
        CHECK((peak || ser));
        CHECK(ser == (refusals.count(r["trial"].str()) == 1));
    }

    // Identical fold assignments: every classifier's out-of-fold predictions
    // name the same trial with the same test fold, as folds.assignment[0] says.
    const auto& first = j["folds"]["assignment"][std::size_t{0}].arr();
    for (const auto& c : cs) {
        const auto& preds = c["first_repeat_predictions"].arr();
        REQUIRE(preds.size() == ids.size());
        for (std::size_t i = 0; i < preds.size(); ++i) {
            CHECK(preds[i]["trial"].str() == ids[i].str());
            CHECK(preds[i]["fold"].num() == first[i].num());
            CHECK(preds[i]["fold"].num() == cs[0]["first_repeat_predictions"][i]["fold"].num());
        }
        CHECK(c["trials_used"].arr().size() == ids.size());
    }
    CHECK(j["paired_differences"].arr().size() == 1);
}

TEST_CASE("trials=all gives a series classifier every trial its rule accepts, the peak rule's refused ones too",
          "[series][pipeline]") {
    InputOptions all;
    all.trials = TrialSelection::series_accepted;
    auto ev = evaluate_prepared(rows(), stock_run_dir(), {rocket()}, small(), all);
    REQUIRE(ev.ok());
    CHECK(ev->selection == "series_accepted");
    CHECK(ev->input == "series");
    const auto refusals = series_refusals();
    CHECK(ev->clean == rows().size() - refusals.size());
    CHECK(ev->refused.size() == refusals.size());
    std::size_t paper_refused_used = 0;
    for (const auto& r : rows())
        if (!r.clean && !refusals.count(r.trial_id)) ++paper_refused_used;
    CHECK(std::count_if(ev->trial_ids.begin(), ev->trial_ids.end(), [&](const std::string& id) {
              return std::find_if(rows().begin(), rows().end(), [&](const features::FeatureRow& r) {
                         return r.trial_id == id && !r.clean;
                     }) != rows().end();
          }) == static_cast<std::ptrdiff_t>(paper_refused_used));
    // Their count is no clean count (the paper's rule refuses some): the text says "used" (first-day review).
    const std::string text = format_evaluation(*ev);
    CHECK_THAT(text, Catch::Contains("trials " + std::to_string(rows().size()) + ", used " + std::to_string(ev->clean) +
                                     ", classes ") &&
                         !Catch::Contains(", clean " + std::to_string(ev->clean)));
    auto clean = evaluate_prepared(rows(), stock_run_dir(), {rocket()}, small(), InputOptions{});
    REQUIRE(clean.ok());
    CHECK_THAT(format_evaluation(*clean), Catch::Contains(", clean " + std::to_string(clean->clean) + ", classes "));
    // So does the page, which says which rule chose them (user review: "trials / clean 270 / 250" under
    // "clean 234 of 270", the series rule never named, rows with more trials evaluated than clean).
    report::ReportInputs in;
    in.dataset_dir = stock_run_dir();
    in.rows = rows();
    in.evaluation = *ev;
    const auto page = report::render_report(in);
    REQUIRE(page.ok());
    CHECK_THAT(*page, Catch::Contains("trials / used") && !Catch::Contains("trials / clean") &&
                          Catch::Contains("id=\"trial-selection\">trials: every trial the series rule accepts") &&
                          Catch::Contains("a row may have more trials evaluated than clean"));
    // And the terminal's summary, whose first line counts the clean trials: the next says which were used.
    CHECK_THAT(report::text_summary(in),
               Catch::Contains("\n  trials: every trial the series rule accepts, the paper's refused ones included (" +
                               std::to_string(ev->clean) + " used, "));
    in.evaluation = *clean;
    CHECK_THAT(report::text_summary(in), Catch::Contains("\n  trials: the paper's clean trials that the series rule "
                                                         "also accepts (" + std::to_string(clean->clean) + " used, "));
    const auto clean_page = report::render_report(in);
    REQUIRE(clean_page.ok());
    CHECK_THAT(*clean_page, Catch::Contains("trials / clean") && !Catch::Contains("more trials evaluated than clean"));

    // A feature classifier has no features for the peak rule's refused trials.
    auto mixed = evaluate_prepared(rows(), stock_run_dir(), {trees(), rocket()}, small(), all);
    REQUIRE_FALSE(mixed.ok());
    CHECK_THAT(mixed.error().message, Catch::Contains("trials=all") && Catch::Contains("trials=clean"));
}

TEST_CASE("the input step refuses a series classifier without recorded trials, and bad option words",
          "[series][pipeline][errors]") {
    auto none = evaluate_prepared(rows(), {}, {rocket()}, small());
    REQUIRE_FALSE(none.ok());
    CHECK_THAT(none.error().message, Catch::Contains("not a dataset folder") && Catch::Contains("features CSV"));

    // Features only: exactly the paper's clean trials, reasons as they always read.
    auto f = make_input_tables(rows(), {}, {ClassifierInput::features}, {});
    REQUIRE(f.ok());
    REQUIRE(f->tables.size() == 1);
    std::vector<std::size_t> row_of;
    const FeatureTable paper = features::to_feature_table(rows(), &row_of);
    CHECK(f->tables[0].x == paper.x);
    CHECK(f->tables[0].y == paper.y);
    CHECK(f->row_of == row_of);
    for (const auto& r : f->refused) CHECK(r.reason.find("peak rule") == std::string::npos);

    CHECK_THAT(parse_trial_selection("some").error().message, Catch::Contains("'clean'") && Catch::Contains("'all'"));
    CHECK(*parse_trial_selection("all") == TrialSelection::series_accepted);
    CHECK_THAT(parse_amplitude("loud").error().message, Catch::Contains("z_per_channel"));
    CHECK(*parse_amplitude("z_per_channel") == series::Amplitude::z_per_channel);
}
