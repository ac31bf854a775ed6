// Grouped and blocked cross-validation (analysis/learn/cv_scheme.hpp): groups
// never straddle training and test, a speed is held out whole, unknown columns
// and groupings that are the class are refused, and the evaluation reports the
// schemes beside random k-fold.
#include <catch2/catch.hpp>

#include <map>
#include <set>

#include "analysis/learn/cv_scheme.hpp"
#include "analysis/learn/evaluate.hpp"
#include "learn_fixtures.hpp"

using namespace rollsense;
using namespace rollsense::learn;
using features::FeatureRow;

namespace {

// 3 objects x 3 speeds x `runs`, recorded object by object as the stock script does.
std::vector<FeatureRow> protocol_rows(int runs, bool with_mount) {
    std::vector<FeatureRow> rows;
    int mount = 0;
    for (const char* object : {"C1", "S1", "P1"}) {
        ++mount;
        int index = 0;
        for (const char* speed : {"10", "15", "20"})
            for (int r = 1; r <= runs; ++r) {
                FeatureRow row;
                row.object = object;
                row.speed = speed;
                row.repetition = r;
                row.trial_id = std::string(object) + "-v" + speed + "-r" + std::to_string(r);
                row.clean = true;
                if (with_mount) {
                    row.extra["mount"] = std::to_string(mount);
                    row.extra["index_in_mount"] = std::to_string(index);
                }
                ++index;
                rows.push_back(row);
            }
    }
    return rows;
}

std::vector<std::size_t> all_rows(std::size_t n) {
    std::vector<std::size_t> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = i;
    return out;
}

std::vector<int> labels_of(const std::vector<FeatureRow>& rows, std::vector<std::string>& names) {
    std::map<std::string, int> index;
    std::vector<int> out;
    for (const auto& r : rows) {
        auto [it, added] = index.emplace(r.object, static_cast<int>(names.size()));
        if (added) names.push_back(r.object);
        out.push_back(it->second);
    }
    return out;
}

// The scheme's groups over every row, then its plan.
Result<FoldPlan> plan_for(const CvScheme& scheme, const std::vector<FeatureRow>& rows, int k, int repeats) {
    auto groups = scheme_groups(scheme, rows, all_rows(rows.size()));
    if (!groups) return groups.error();
    std::vector<std::string> names;
    const auto labels = labels_of(rows, names);
    return make_scheme_plan(scheme, labels, names, *groups, k, repeats, 1);
}

// Every group's rows sit in one fold of every repetition.
void check_groups_whole(const FoldPlan& plan, const std::vector<std::string>& groups) {
    for (const auto& fold : plan.assignment) {
        std::map<std::string, std::set<int>> folds_of;
        for (std::size_t i = 0; i < groups.size(); ++i) folds_of[groups[i]].insert(fold[i]);
        for (const auto& [g, f] : folds_of) CHECK(f.size() == 1);
    }
}

}  // namespace

TEST_CASE("cv schemes: --cv, --group-by and --block parsed, mistakes named", "[learn][cv_scheme]") {
    auto none = parse_cv_schemes("random", "", "");
    REQUIRE(none.ok());
    CHECK(none->empty());
    auto both = parse_cv_schemes("random,blocked,grouped", "speed", "10");
    REQUIRE(both.ok());
    REQUIRE(both->size() == 2);
    CHECK((*both)[0].id() == "blocked:10");
    CHECK((*both)[1].id() == "grouped:speed");
    CHECK_THAT(parse_cv_schemes("shuffled", "", "").error().message, Catch::Contains("unknown scheme 'shuffled'"));
    CHECK_THAT(parse_cv_schemes("grouped", "", "").error().message, Catch::Contains("needs --group-by"));
    CHECK_THAT(parse_cv_schemes("random", "speed", "").error().message, Catch::Contains("add grouped to --cv"));
    CHECK_THAT(parse_cv_schemes("blocked", "", "").error().message, Catch::Contains("needs --block"));
    CHECK_THAT(parse_cv_schemes("blocked", "", "0").error().message, Catch::Contains("integer >= 1"));
    CHECK_THAT(parse_cv_schemes("blocked", "", "5x").error().message, Catch::Contains("'5x'"));
}

TEST_CASE("grouped by speed: leave one speed out, each speed held out whole", "[learn][cv_scheme]") {
    const auto rows = protocol_rows(6, false);
    const auto scheme = parse_cv_schemes("grouped", "speed", "")->front();
    auto groups = scheme_groups(scheme, rows, all_rows(rows.size()));
    REQUIRE(groups.ok());
    std::vector<std::string> names;
    const auto labels = labels_of(rows, names);
    auto plan = make_scheme_plan(scheme, labels, names, *groups, 5, 10, 1);
    REQUIRE(plan.ok());
    CHECK(plan->folds == 3);      // three speeds, fewer than 5 folds: leave one out
    CHECK(plan->repeats() == 1);  // deterministic, so once
    check_groups_whole(*plan, *groups);
    std::set<int> folds(plan->assignment[0].begin(), plan->assignment[0].end());
    CHECK(folds.size() == 3);
}

TEST_CASE("blocked: N consecutive rolls of a mount form a group", "[learn][cv_scheme]") {
    for (bool with_mount : {true, false}) {
        const auto rows = protocol_rows(10, with_mount);  // 30 rolls per mount
        const auto scheme = parse_cv_schemes("blocked", "", "5")->front();
        auto groups = scheme_groups(scheme, rows, all_rows(rows.size()));
        REQUIRE(groups.ok());
        CHECK(std::set<std::string>(groups->begin(), groups->end()).size() == 18);  // 3 mounts x 6 blocks
        CHECK((*groups)[0] == (*groups)[4]);
        CHECK((*groups)[4] != (*groups)[5]);
        std::vector<std::string> names;
        const auto labels = labels_of(rows, names);
        auto plan = make_scheme_plan(scheme, labels, names, *groups, 5, 3, 7);
        REQUIRE(plan.ok());
        CHECK(plan->folds == 5);
        CHECK(plan->repeats() == 3);
        check_groups_whole(*plan, *groups);
    }
    SECTION("only the used rows get groups, counted over every roll") {
        const auto rows = protocol_rows(10, false);
        const auto scheme = parse_cv_schemes("blocked", "", "5")->front();
        auto groups = scheme_groups(scheme, rows, {0, 4, 5, 29});
        REQUIRE(groups.ok());
        CHECK(*groups == std::vector<std::string>{"C1#0", "C1#0", "C1#1", "C1#5"});
    }
}

TEST_CASE("grouped CV refuses an unknown column and a grouping that is the class", "[learn][cv_scheme]") {
    const auto rows = protocol_rows(4, true);
    auto unknown = scheme_groups(parse_cv_schemes("grouped", "session", "")->front(), rows, all_rows(rows.size()));
    REQUIRE_FALSE(unknown.ok());
    CHECK_THAT(unknown.error().message, Catch::Contains("no manifest column 'session'"));
    CHECK_THAT(unknown.error().message, Catch::Contains("speed, repetition, index_in_mount, mount"));

    // One mount per object: leaving a mount out leaves its class out of training.
    auto plan = plan_for(parse_cv_schemes("grouped", "mount", "")->front(), rows, 5, 1);
    REQUIRE_FALSE(plan.ok());
    CHECK_THAT(plan.error().message, Catch::Contains("no training fold ever sees that class"));
    CHECK_THAT(plan.error().message, Catch::Contains("docs/identification.md"));

    // Blocks as long as a mounting are the class as well: the message says to shorten them.
    auto too_long = plan_for(parse_cv_schemes("blocked", "", "12")->front(), rows, 5, 1);
    REQUIRE_FALSE(too_long.ok());
    CHECK_THAT(too_long.error().message, Catch::Contains("too few blocks") && Catch::Contains("smaller blocks"));

    // A single group cannot be cross-validated.
    std::vector<std::string> names;
    const auto labels = labels_of(rows, names);
    auto one = make_scheme_plan(parse_cv_schemes("grouped", "mount", "")->front(), labels, names,
                                std::vector<std::string>(rows.size(), "1"), 5, 1, 1);
    CHECK_THAT(one.error().message, Catch::Contains("at least 2"));
}

TEST_CASE("evaluation reports grouped and blocked CV beside random k-fold", "[learn][cv_scheme][evaluate]") {
    auto rows = protocol_rows(12, true);
    // Features that tell the objects apart, with a little spread per roll.
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double cls = rows[i].object == "C1" ? 0.0 : rows[i].object == "S1" ? 1.0 : 2.0;
        for (std::size_t k = 0; k < rows[i].values.size(); ++k)
            rows[i].values[k] = cls * (k + 1) + 0.01 * static_cast<double>((i * 7 + k) % 5);
    }
    EvaluationOptions o;
    o.folds = 3;
    o.repeats = 2;
    o.schemes = *parse_cv_schemes("blocked,grouped", "speed", "6");
    auto ev = evaluate_features(rows, {ClassifierRequest{"bagged_trees", fixtures::bagged_trees_factory(), {}}}, o);
    REQUIRE(ev.ok());
    REQUIRE(ev->schemes.size() == 2);
    CHECK(ev->schemes[0].groups == 18);  // 3 mounts x 36 rolls / 6
    CHECK(ev->schemes[1].groups == 3);
    const auto& c = ev->primary();
    REQUIRE(c.scheme_cv.size() == 2);
    CHECK(c.scheme_cv[0].cv.total == rows.size() * 2);  // every trial out of fold, in each of 2 repetitions
    CHECK(c.scheme_cv[1].cv.total == rows.size());      // leave-one-speed-out: once
    CHECK(c.scheme_cv[1].cv.mean > 0.9);
    const std::string text = format_evaluation(*ev);
    CHECK_THAT(text, Catch::Contains("grouped by speed, 1 x 3-fold CV"));
    CHECK_THAT(text, Catch::Contains("blocked: 6 consecutive trials within a mount, 2 x 3-fold CV"));
}
