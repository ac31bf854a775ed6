// Where identification before the roll ends cuts its prefixes: from the
// contact's onset (series::contact_onset), as the paper's timing rule asks,
// not from record_start. The onset is found causally, as a live run finds it;
// a contact that begins later in the recording gives the same prefix rows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/learn/prefix_evaluation.hpp"
#include "analysis/series/onset.hpp"
#include "analysis/series/prepare.hpp"
#include "synthetic.hpp"

using namespace rollsense;
using rollsense::testing::make_trial;
using rollsense::testing::SyntheticTrial;

namespace {

const std::vector<std::size_t> kAll{0, 1, 2};

TrialRecord record(const std::string& id, const std::string& speed) {
    TrialRecord r;
    r.info.id = id;
    r.info.object = "C1";
    r.info.speed = speed;
    return r;
}

std::vector<double> prefix_row(const TrialData& t, std::size_t keep) {
    series::SeriesSettings s;
    s.prefix = keep;
    auto p = series::prepare_series(t, kAll, s);
    REQUIRE(p.ok());
    REQUIRE(p->ok);
    return p->values;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    REQUIRE(a.size() == b.size());
    double d = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

}  // namespace

TEST_CASE("the contact's onset is the first sample a channel reads min_amplitude above its rest", "[series][prefix]") {
    const TrialData t = make_trial({});
    const series::SeriesSettings s;
    const auto onset = series::contact_onset(t, kAll, s);
    REQUIRE(onset);
    CHECK(*onset > 50);   // the contact begins at 50; the first bump needs a few samples to rise 0.03
    CHECK(*onset < 80);
    bool above = false;
    for (std::size_t c = 0; c < 3; ++c) above = above || t.channels[c][*onset] - t.channels[c][0] >= s.min_amplitude;
    CHECK(above);
    for (std::size_t c = 0; c < 3; ++c) CHECK(t.channels[c][*onset - 1] - t.channels[c][0] < s.min_amplitude);

    SECTION("causal: a live recording that has just reached it finds it; one sample earlier it is not there") {
        series::SeriesSettings live = s;
        live.prefix = *onset + 1;
        CHECK(series::contact_onset(t, kAll, live) == onset);
        live.prefix = *onset;
        CHECK_FALSE(series::contact_onset(t, kAll, live));
    }
    SECTION("a recording whose sensors never rise has none") {
        TrialData flat = t;
        for (auto& ch : flat.channels) std::fill(ch.begin(), ch.end(), 0.5);
        CHECK_FALSE(series::contact_onset(flat, kAll, s));
    }
    SECTION("invalid samples are skipped, not read as a rise") {
        TrialData spiky = t;
        spiky.channels[1][10] = 99.0;
        spiky.valid[10] = 0;
        CHECK(series::contact_onset(spiky, kAll, s) == onset);
    }
}

TEST_CASE("a prefix keeps the onset plus a fraction of the nominal length after it", "[series][prefix]") {
    CHECK(learn::prefix_samples(0.5, 40, 100.0, 200) == 90);
    CHECK(learn::prefix_samples(0.5, 150, 100.0, 200) == 200);  // never more than the recording has
    CHECK(learn::prefix_samples(1.0, 40, 100.0, 200) == 200);   // the whole roll, whatever the onset
    CHECK(learn::prefix_samples(1.0, std::nullopt, 100.0, 200) == 200);
    CHECK(learn::prefix_samples(0.5, std::nullopt, 100.0, 200) == 0);  // no contact yet: nothing to decide on
}

TEST_CASE("a contact that begins later in the recording gives the same prefixes (time runs from the contact)",
          "[series][prefix]") {
    // Two rolls of one object at one speed; in the second the object first
    // touches the array 20 samples later (placed further along), and its
    // recording is 20 samples longer, so the roll after the onset is the same.
    const TrialData early = make_trial({.samples = 200, .contact_start = 50.0});
    const TrialData late = make_trial({.samples = 220, .contact_start = 70.0});
    const std::vector<TrialRecord> records{record("a", "10"), record("b", "10")};
    const std::vector<TrialData> data{early, late};
    const learn::PrefixCuts cuts = learn::prefix_cuts(records, data, kAll, {});
    REQUIRE(cuts.onset[0]);
    REQUIRE(cuts.onset[1]);
    CHECK(*cuts.onset[1] == *cuts.onset[0] + 20);
    REQUIRE(cuts.nominal.size() == 1);
    CHECK(cuts.nominal[0].samples == static_cast<double>(early.samples() - *cuts.onset[0]));
    CHECK(cuts.nominal[0].trials == 2);

    int told_apart_from_start = 0;
    for (double f : {0.3, 0.5, 0.7}) {
        INFO("fraction " << f);
        const std::size_t keep_early = cuts.keep(0, f, early.samples());
        const std::size_t keep_late = cuts.keep(1, f, late.samples());
        CHECK(keep_late == keep_early + 20);
        CHECK(max_abs_diff(prefix_row(early, keep_early), prefix_row(late, keep_late)) < 1e-9);

        // Cut from record_start instead (f × the median recording length, the
        // rule before), the later contact shows less of itself while it is
        // still running: a classifier could tell the placements apart by the
        // onset's timing alone.
        series::SeriesSettings s;
        s.prefix = static_cast<std::size_t>(std::llround(f * 210.0));
        auto a = series::prepare_series(early, kAll, s), b = series::prepare_series(late, kAll, s);
        REQUIRE(a.ok());
        REQUIRE(b.ok());
        if (a->ok != b->ok || (a->ok && max_abs_diff(a->values, b->values) > 1e-3)) ++told_apart_from_start;
    }
    CHECK(told_apart_from_start >= 2);
}
