// Grouped and blocked cross-validation (analysis/learn/cv_scheme.hpp): groups
// never straddle training and test, a speed is held out whole, unknown columns
// and groupings that are the class are refused, and the evaluation reports the
// schemes beside random k-fold; tuning under a scheme uses folds of the same
// kind, built from the outer training trials only.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <map>
#include <set>
#include <tuple>

#include "analysis/learn/cv_scheme.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/tuning.hpp"
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

// Every trial's features tell its object apart, with a little spread per roll.
void separate_objects(std::vector<FeatureRow>& rows) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double cls = rows[i].object == "C1" ? 0.0 : rows[i].object == "S1" ? 1.0 : 2.0;
        for (std::size_t k = 0; k < rows[i].values.size(); ++k)
            rows[i].values[k] = cls * (k + 1) + 0.01 * static_cast<double>((i * 7 + k) % 5);
    }
}

// 3 folds, one repetition, two optimiser points on tiny forests: tuning, quickly.
EvaluationOptions quick_tuning(std::vector<CvScheme> schemes) {
    EvaluationOptions o;
    o.folds = 3;
    o.repeats = 1;
    o.optimize = true;
    o.bayes.evaluations = 2;
    o.params.set("learners", std::int64_t{3});
    o.schemes = std::move(schemes);
    return o;
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
    // Review: they came in the program's order (blocked first) whatever was asked; a scheme named twice runs once.
    auto asked = parse_cv_schemes("grouped,random,blocked,grouped", "speed", "10");
    REQUIRE(asked.ok());
    REQUIRE(asked->size() == 2);
    CHECK((*asked)[0].id() == "grouped:speed");
    CHECK((*asked)[1].id() == "blocked:10");
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
    CHECK_THAT(plan.error().message, Catch::Contains("its clean trials all have mount '1', one group"));

    // Review (user journeys) item 10: grouped by speed where one class's clean trials are all at one speed, the
    // advice was to group by speed. It names that class's one speed now.
    std::vector<FeatureRow> one_speed;
    for (const auto& r : rows)
        if (r.object != "S1" || r.speed == "15") one_speed.push_back(r);
    auto by_speed = plan_for(parse_cv_schemes("grouped", "speed", "")->front(), one_speed, 5, 1);
    REQUIRE_FALSE(by_speed.ok());
    CHECK_THAT(by_speed.error().message, Catch::Contains("class 'S1'") &&
                                             Catch::Contains("its clean trials all have speed '15', one group") &&
                                             Catch::Contains("record more of it, or use --cv blocked"));

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
    separate_objects(rows);
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

// --- Tuning folds follow the scheme (analysis/learn/tuning.hpp) ---

namespace {

// For every outer fold of `rule` over all rows, the tuning folds built from
// its training rows: how many tuning validation folds share a group with
// their tuning training rows (0 = no leak).
int tuning_folds_sharing_groups(const TuningFoldRule& rule, const std::vector<int>& labels,
                                const std::vector<std::string>& names, const std::vector<std::string>& groups, int k) {
    auto outer = tuning_folds(rule, labels, names, all_rows(labels.size()), k, 7920);
    REQUIRE(outer.ok());
    int sharing = 0;
    for (int f = 0; f < outer->k; ++f) {
        const auto train = fold_rows(outer->fold, f, false);
        auto inner = tuning_folds(rule, labels, names, train, k, 104730 + static_cast<std::uint64_t>(f));
        REQUIRE(inner.ok());
        REQUIRE(inner->fold.size() == train.size());
        for (int g = 0; g < inner->k; ++g) {
            std::set<std::string> validation, training;
            for (std::size_t i = 0; i < train.size(); ++i)
                (inner->fold[i] == g ? validation : training).insert(groups[train[i]]);
            for (const auto& v : validation) {
                if (training.count(v)) {
                    ++sharing;
                    break;
                }
            }
        }
        // The outer test fold's trials never enter its tuning folds.
        for (std::size_t r : train) CHECK(outer->fold[r] != f);
    }
    return sharing;
}

}  // namespace

TEST_CASE("tuning folds of a grouped or blocked CV share no group with their training trials",
          "[learn][cv_scheme][tuning]") {
    const auto rows = protocol_rows(12, true);
    std::vector<std::string> names;
    const auto labels = labels_of(rows, names);
    for (const auto& [list, by, block] : std::vector<std::tuple<std::string, std::string, std::string>>{
             {"grouped", "speed", ""}, {"grouped", "repetition", ""}, {"blocked", "", "6"}}) {
        INFO(list << " " << by << block);
        const auto scheme = parse_cv_schemes(list, by, block)->front();
        const auto groups = *scheme_groups(scheme, rows, all_rows(rows.size()));
        const TuningFoldRule rule{&scheme, &groups};
        CHECK(tuning_folds_sharing_groups(rule, labels, names, groups, 3) == 0);
        // Random tuning folds on the same trials put neighbours on both sides:
        // the check above can fail.
        CHECK(tuning_folds_sharing_groups(TuningFoldRule{}, labels, names, groups, 3) > 0);
    }
    SECTION("a speed held out by the outer folds leaves its tuning folds the other speeds, one each") {
        const auto scheme = parse_cv_schemes("grouped", "speed", "")->front();
        const auto groups = *scheme_groups(scheme, rows, all_rows(rows.size()));
        const TuningFoldRule rule{&scheme, &groups};
        auto outer = tuning_folds(rule, labels, names, all_rows(rows.size()), 5, 1);
        REQUIRE(outer.ok());
        CHECK(outer->k == 3);  // leave one speed out
        auto inner = tuning_folds(rule, labels, names, fold_rows(outer->fold, 0, false), 5, 2);
        REQUIRE(inner.ok());
        CHECK(inner->k == 2);  // the two remaining speeds, one out at a time
    }
    SECTION("random rule: the paper's stratified folds, unchanged") {
        auto random = tuning_folds(TuningFoldRule{}, labels, names, all_rows(rows.size()), 5, 11);
        REQUIRE(random.ok());
        CHECK(random->k == 5);
        CHECK(random->fold == *stratified_folds(labels, 5, 11));
        CHECK(TuningFoldRule{}.describe() == "random stratified");
    }
}

TEST_CASE("tuning folds that a training set's groups cannot make are an error, never random folds",
          "[learn][cv_scheme][tuning]") {
    // Two speeds: leaving one out leaves one speed to tune on, which cannot be cross-validated.
    auto rows = protocol_rows(6, true);
    rows.erase(std::remove_if(rows.begin(), rows.end(), [](const FeatureRow& r) { return r.speed == "20"; }),
               rows.end());
    separate_objects(rows);
    const EvaluationOptions o = quick_tuning(*parse_cv_schemes("grouped", "speed", ""));
    auto ev = evaluate_features(rows, {ClassifierRequest{"bagged_trees", fixtures::bagged_trees_factory(), o.params}}, o);
    REQUIRE_FALSE(ev.ok());
    CHECK_THAT(ev.error().describe(), Catch::Contains("nested CV outer fold 1") &&
                                          Catch::Contains("its tuning folds (grouped by speed") &&
                                          Catch::Contains("at least 2"));
}

TEST_CASE("evaluation with optimize tunes each grouped or blocked CV on folds of its own kind",
          "[learn][cv_scheme][tuning][evaluate]") {
    auto rows = protocol_rows(12, true);
    separate_objects(rows);
    const EvaluationOptions o = quick_tuning(*parse_cv_schemes("blocked", "", "6"));
    auto ev = evaluate_features(rows, {ClassifierRequest{"bagged_trees", fixtures::bagged_trees_factory(), o.params}}, o);
    REQUIRE(ev.ok());
    const auto& c = ev->primary();
    REQUIRE(c.tuned);
    REQUIRE(c.nested);
    REQUIRE(c.scheme_cv.size() == 1);
    const auto& s = c.scheme_cv[0];
    REQUIRE(s.tuned);
    REQUIRE(s.nested);
    CHECK(s.tuned->search.history.size() == 2);
    CHECK(s.nested->outer_accuracy.size() == 3);
    CHECK(s.nested->total == rows.size());
    const std::string text = format_evaluation(*ev);
    CHECK_THAT(text, Catch::Contains("tuning folds blocked: 6 consecutive trials within a mount too") &&
                         Catch::Contains("nested CV, outer and tuning folds blocked: 6 consecutive trials"));
    // The random k-fold's tuning reads as it always did.
    CHECK_THAT(text, Catch::Contains("nested CV (tuning inside each outer training fold): the honest tuned figure"));
}

namespace {

// A classifier that notes, for every prediction, whether the row's group
// (column 0) was among its training rows: a tuning fold that shares a group
// with its training folds shows up as a leak.
class GroupSpy final : public Classifier {
public:
    explicit GroupSpy(std::atomic<int>* leaks) : leaks_(leaks) {}
    SearchSpace search_space(std::size_t, std::size_t) const override {
        return {SearchDimension{"learners", SearchDimension::Scale::integer_linear, 1, 9, {}}};
    }
    Status train(const FeatureTable& data) override {
        names_ = data.class_names;
        for (std::size_t i = 0; i < data.rows; ++i) seen_.insert(data.row(i)[0]);
        return {};
    }
    Result<Prediction> predict(std::span<const double> row) const override {
        if (seen_.count(row[0])) ++*leaks_;
        Prediction p;
        p.label = 0;
        p.class_name = names_[0];
        p.scores.assign(names_.size(), 0.0);
        p.scores[0] = 1.0;
        return p;
    }
    std::vector<std::string> class_names() const override { return names_; }
    Status save(const std::filesystem::path&) const override { return {}; }
    Status load(const std::filesystem::path&) override { return {}; }

private:
    std::atomic<int>* leaks_;
    std::vector<std::string> names_;
    std::set<double> seen_;
};

}  // namespace

TEST_CASE("the deployed model's tuning folds follow the scheme: no tuning prediction sees its group in training",
          "[learn][cv_scheme][tuning][fit_final]") {
    auto rows = protocol_rows(12, true);
    for (auto& r : rows) r.values.fill(static_cast<double>(r.repetition));  // column 0: the group (repetition)
    std::atomic<int> leaks{0};
    const ClassifierFactory spy = [&leaks](const ParamSet&) -> Result<ClassifierPtr> {
        return ClassifierPtr(std::make_shared<GroupSpy>(&leaks));
    };
    EvaluationOptions o;
    o.folds = 3;
    o.optimize = true;
    o.bayes.evaluations = 3;
    o.schemes = *parse_cv_schemes("grouped", "repetition", "");
    auto grouped = fit_final(rows, spy, o);
    REQUIRE(grouped.ok());
    CHECK(grouped->tuning_folds == "3-fold, grouped by repetition");
    CHECK(leaks == 0);

    o.schemes.clear();  // the paper's random stratified tuning folds: neighbours on both sides
    auto random = fit_final(rows, spy, o);
    REQUIRE(random.ok());
    CHECK(random->tuning_folds == "3-fold, random stratified");
    CHECK(leaks > 0);

    o.schemes = *parse_cv_schemes("blocked,grouped", "repetition", "6");
    auto two = fit_final(rows, spy, o);
    REQUIRE_FALSE(two.ok());
    CHECK_THAT(two.error().message, Catch::Contains("needs one fold scheme") && Catch::Contains("blocked:6"));
}
