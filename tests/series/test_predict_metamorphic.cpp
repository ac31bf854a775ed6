// The series rule's metamorphic properties where they matter, at the level of
// the answer: a MiniRocket trained on one small simulated run predicts the
// trials of another (and the other way round), and changes that the rule is
// meant to absorb — the contact crossing the array 1.5× slower, one invalid
// sample, a constant offset on a channel — must leave the predictions as they
// are (the preparation-level tests are in test_prepare.cpp and
// test_series_table.cpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include "analysis/learn/cross_validation.hpp"
#include "analysis/series/series_table.hpp"
#include "classifier_factory.hpp"
#include "rollsense/minirocket/minirocket.hpp"
#include "run_command.hpp"
#include "stretch.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::series;

namespace {

const std::vector<std::string> kChannels{"ch1", "ch2", "ch3"};
const std::vector<std::size_t> kChannelIdx{0, 1, 2};

// A small stock run of its own seed: four runs per object and speed, 108
// trials. (Models trained on fewer cannot resolve the 5 % the rule promises:
// trained on 27 trials, one borderline flip among 75 answers is 1.3 %.)
DatasetReader record_small_run(const rollsense::testing::TempDir& dir, int seed) {
    const auto out = dir.path() / "run";
    const auto run = rollsense::testing::run_rollsense(
        "run " + std::string(ROLLSENSE_SOURCE_DIR) +
        "/scripts/paper_experiment.lua --profile sim --set runs=4 --set analyse=false --seed " + std::to_string(seed) +
        " -q --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    auto reader = DatasetReader::open(out);
    REQUIRE(reader.ok());
    return *reader;
}

struct SmallRun {
    explicit SmallRun(int seed) : dir("rollsense-series-seed-" + std::to_string(seed)), reader(record_small_run(dir, seed)) {}
    rollsense::testing::TempDir dir;
    DatasetReader reader;
};

const DatasetReader& small_run(int seed) {
    static std::map<int, std::unique_ptr<SmallRun>> runs;
    auto& run = runs[seed];
    if (!run) run = std::make_unique<SmallRun>(seed);
    return run->reader;
}

learn::ClassifierPtr trained_on(const DatasetReader& run) {
    auto table = series_table(run, run.trials(), kChannels, {}, 2);
    REQUIRE(table.ok());
    ParamSet p;
    p.set("threads", std::int64_t{2});
    auto model = learn::train_classifier(
        table->table, rollsense::testing::factory_of<minirocket::MiniRocket>(minirocket::minirocket_schema()), p);
    REQUIRE(model.ok());
    return *model;
}

// What a change does to the predictions of one model on one run's trials.
struct Tally {
    std::size_t predicted = 0;  // trials the rule accepts unchanged
    std::size_t changed = 0;    // of them, the answer differs after the change
    std::size_t refused = 0;    // of them, the changed trial is refused
};

template <typename Change>
void tally(const learn::ClassifierPtr& model, const DatasetReader& run, Change change, Tally& t) {
    for (const auto& rec : run.trials()) {
        auto data = run.load(rec);
        REQUIRE(data.ok());
        auto base = prepare_series(*data, kChannelIdx, {});
        REQUIRE(base.ok());
        if (!base->ok) continue;
        INFO(rec.info.id);
        auto before = model->predict(base->values);
        REQUIRE(before.ok());
        auto changed = prepare_series(change(*data, *base), kChannelIdx, {});
        REQUIRE(changed.ok());
        ++t.predicted;
        if (!changed->ok) {
            ++t.refused;
            continue;
        }
        auto after = model->predict(changed->values);
        REQUIRE(after.ok());
        if (after->label != before->label) ++t.changed;
    }
}

// Both directions: trained on one small run, predicting the other, and back.
template <typename Change>
Tally both_ways(Change change) {
    static const auto on_a = trained_on(small_run(12));
    static const auto on_b = trained_on(small_run(13));
    Tally t;
    tally(on_a, small_run(13), change, t);
    tally(on_b, small_run(12), change, t);
    return t;
}

}  // namespace

TEST_CASE("stretching only the contact 1.5x in time changes fewer than 5 % of predictions",
          "[series][metamorphic][predict]") {
    const auto t = both_ways([](const TrialData& d, const PreparedSeries& p) {
        // From the window's start to its end (contact and margins), as at the preparation level.
        const double a = std::max(0.0, std::floor(p.window_start));
        const double b = std::min(static_cast<double>(d.samples() - 1), std::ceil(p.window_end));
        return rollsense::testing::stretch_contact(d, a, b, 1.5);
    });
    INFO(t.changed << " of " << t.predicted << " predictions changed, " << t.refused << " refused");
    CHECK(t.predicted >= 65);  // of 81 trials; the rule accepts about 90 %
    CHECK(t.refused == 0);
    CHECK(static_cast<double>(t.changed) < 0.05 * static_cast<double>(t.predicted));
}

TEST_CASE("a trial with one invalid sample in its contact still classifies, almost always the same",
          "[series][metamorphic][predict]") {
    const auto t = both_ways([](const TrialData& d, const PreparedSeries& p) {
        TrialData broken = d;
        const auto mid = static_cast<std::size_t>(0.5 * (p.window_start + p.window_end));
        broken.channels[1][mid] = std::numeric_limits<double>::quiet_NaN();  // a failed read on ch2
        return broken;
    });
    INFO(t.changed << " of " << t.predicted << " predictions changed, " << t.refused << " refused");
    CHECK(t.predicted >= 65);
    CHECK(t.refused == 0);
    CHECK(static_cast<double>(t.changed) < 0.05 * static_cast<double>(t.predicted));
}

TEST_CASE("a constant offset on a channel changes no prediction", "[series][metamorphic][predict]") {
    const auto t = both_ways([](const TrialData& d, const PreparedSeries&) {
        TrialData shifted = d;
        for (double& v : shifted.channels[2]) v += 0.75;  // ch3 reads 0.75 kPa higher throughout
        return shifted;
    });
    INFO(t.changed << " of " << t.predicted << " predictions changed, " << t.refused << " refused");
    CHECK(t.predicted >= 65);
    CHECK(t.refused == 0);
    CHECK(t.changed == 0);
}
