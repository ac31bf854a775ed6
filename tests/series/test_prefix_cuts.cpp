// Where identification before the roll ends cuts its prefixes: on the
// contact's own clock (series::contact_clock), as the paper's timing rule
// asks: from the onset, never from record_start, and in the contact's unit,
// never in samples or seconds. The clock is read causally, as a live run
// reads it. A contact that begins later gives the same prefix rows, and so
// does a contact that crosses the array more slowly.
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

series::PreparedSeries prefix_of(const TrialData& t, std::size_t keep) {
    series::SeriesSettings s;
    s.prefix = keep;
    auto p = series::prepare_series(t, kAll, s);
    REQUIRE(p.ok());
    return *p;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    REQUIRE(a.size() == b.size());
    double d = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

// Rows of two trials that differ (or one refused and the other not).
bool told_apart(const series::PreparedSeries& a, const series::PreparedSeries& b) {
    return a.ok != b.ok || (a.ok && max_abs_diff(a.values, b.values) > 1e-3);
}

}  // namespace

TEST_CASE("the contact's clock: the onset where a channel rises, the unit where it has been passed", "[series][prefix]") {
    const TrialData t = make_trial({});
    const series::SeriesSettings s;
    const auto clock = series::contact_clock(t, kAll, s);
    REQUIRE(clock);
    const std::size_t onset = clock->onset;
    CHECK(onset > 50);  // the contact begins at 50; the first bump needs a few samples to rise 0.03
    CHECK(onset < 80);
    CHECK(clock->channel == 0);  // the first bump is channel 0's
    CHECK(t.channels[0][onset] - t.channels[0][0] >= s.min_amplitude);
    for (std::size_t c = 0; c < 3; ++c) CHECK(t.channels[c][onset - 1] - t.channels[c][0] < s.min_amplitude);
    REQUIRE(clock->unit);
    const std::size_t passed = onset + *clock->unit;  // channel 0 fell back to half its rise: past its centre at 74
    CHECK(passed > 74);
    const double top = *std::max_element(t.channels[0].begin(), t.channels[0].end());
    CHECK(t.channels[0][passed] <= 0.5 * top + 1e-12);
    CHECK(t.channels[0][passed - 1] > 0.5 * top);

    SECTION("causal: a live recording finds each where it happens, and not one sample earlier") {
        series::SeriesSettings live = s;
        live.prefix = passed + 1;
        auto c = series::contact_clock(t, kAll, live);
        REQUIRE(c);
        CHECK(c->onset == onset);
        CHECK(c->unit == clock->unit);
        live.prefix = passed;
        c = series::contact_clock(t, kAll, live);
        REQUIRE(c);
        CHECK(c->onset == onset);
        CHECK_FALSE(c->unit);
        live.prefix = onset;
        CHECK_FALSE(series::contact_clock(t, kAll, live));
    }
    SECTION("a recording whose sensors never rise has no clock") {
        TrialData flat = t;
        for (auto& ch : flat.channels) std::fill(ch.begin(), ch.end(), 0.5);
        CHECK_FALSE(series::contact_clock(flat, kAll, s));
    }
    SECTION("invalid samples are skipped, not read as a rise") {
        TrialData spiky = t;
        spiky.channels[1][10] = 99.0;
        spiky.valid[10] = 0;
        const auto c = series::contact_clock(spiky, kAll, s);
        REQUIRE(c);
        CHECK(c->onset == onset);
        CHECK(c->unit == clock->unit);
    }
}

TEST_CASE("a prefix keeps the onset plus a fraction of the nominal roll in the trial's units", "[series][prefix]") {
    const series::ContactClock clock{40, 0, 10};
    CHECK(learn::prefix_samples(0.5, clock, 16.0, 200) == 120);   // 40 + 0.5 × 16 × 10
    CHECK(learn::prefix_samples(0.05, clock, 16.0, 200) == 51);   // never before the unit is known (40 + 10 + 1)
    CHECK(learn::prefix_samples(0.9, clock, 30.0, 200) == 200);   // never more than the recording has
    CHECK(learn::prefix_samples(1.0, clock, 16.0, 200) == 200);   // the whole roll
    CHECK(learn::prefix_samples(1.0, std::nullopt, 16.0, 200) == 200);
    CHECK(learn::prefix_samples(0.5, std::nullopt, 16.0, 200) == 0);  // no contact: nothing to decide on
    CHECK(learn::prefix_samples(0.5, series::ContactClock{40, 0, std::nullopt}, 16.0, 200) == 0);  // no unit
}

TEST_CASE("a contact that begins later gives the same prefixes (time runs from the onset)", "[series][prefix]") {
    // Two rolls of one object at one speed; in the second the object first
    // touches the array 20 samples later, and its recording is 20 samples
    // longer, so the roll after the onset is the same.
    const TrialData early = make_trial({.samples = 200, .contact_start = 50.0});
    const TrialData late = make_trial({.samples = 220, .contact_start = 70.0});
    const std::vector<TrialRecord> records{record("a", "10"), record("b", "10")};
    const learn::PrefixCuts cuts = learn::prefix_cuts(records, {early, late}, kAll, {});
    REQUIRE(cuts.clock[0]);
    REQUIRE(cuts.clock[1]);
    CHECK(cuts.clock[1]->onset == cuts.clock[0]->onset + 20);
    CHECK(cuts.clock[1]->unit == cuts.clock[0]->unit);
    REQUIRE(cuts.nominal.size() == 1);
    CHECK(cuts.nominal[0].trials == 2);

    int told_apart_from_start = 0;
    for (double f : {0.3, 0.5, 0.7}) {
        INFO("fraction " << f);
        const std::size_t keep_early = cuts.keep(0, f, early.samples());
        const std::size_t keep_late = cuts.keep(1, f, late.samples());
        CHECK(keep_late == keep_early + 20);
        const auto a = prefix_of(early, keep_early), b = prefix_of(late, keep_late);
        REQUIRE(a.ok);
        REQUIRE(b.ok);
        CHECK(max_abs_diff(a.values, b.values) < 1e-9);
        // Cut from record_start instead (f × the median recording length, the
        // rule before 2026-11-26), the later contact shows less of itself: a
        // classifier could tell the placements apart by the onset's timing.
        const auto from_start = static_cast<std::size_t>(std::llround(f * 210.0));
        if (told_apart(prefix_of(early, from_start), prefix_of(late, from_start))) ++told_apart_from_start;
    }
    CHECK(told_apart_from_start >= 2);
}

TEST_CASE("a contact that crosses the array more slowly gives the same prefixes (time runs in its unit)",
          "[series][prefix]") {
    // One object's pattern crossing at two speeds of its own (a larger or a
    // smaller object at one roll speed): the contact takes 1.5 times longer.
    const TrialData fast = make_trial({.samples = 200, .contact_length = 80.0});
    const TrialData slow = make_trial({.samples = 200, .contact_length = 80.0, .stretch = 1.5});
    const std::vector<TrialRecord> records{record("fast", "10"), record("slow", "10")};
    const learn::PrefixCuts cuts = learn::prefix_cuts(records, {fast, slow}, kAll, {});
    REQUIRE(cuts.clock[0]);
    REQUIRE(cuts.clock[1]);
    REQUIRE(cuts.clock[0]->unit);
    REQUIRE(cuts.clock[1]->unit);
    CHECK(static_cast<double>(*cuts.clock[1]->unit) == Approx(1.5 * static_cast<double>(*cuts.clock[0]->unit)).margin(1.5));

    int told_apart_in_samples = 0;
    for (double f : {0.3, 0.4, 0.5}) {
        INFO("fraction " << f);
        const std::size_t keep_fast = cuts.keep(0, f, fast.samples());
        const std::size_t keep_slow = cuts.keep(1, f, slow.samples());
        const auto a = prefix_of(fast, keep_fast), b = prefix_of(slow, keep_slow);
        REQUIRE(a.ok);
        REQUIRE(b.ok);
        // Whole samples: the cut and the onset move by up to a sample each.
        CHECK(max_abs_diff(a.values, b.values) < 0.08);
        // The same number of samples after the onset instead (a fixed time,
        // the cut before this one), the slower contact shows less of itself:
        // the crossing speed, hence the size, would be read from the prefix.
        const std::size_t after = keep_fast - cuts.clock[0]->onset;
        const auto c = prefix_of(slow, cuts.clock[1]->onset + after);
        if (!c.ok || max_abs_diff(a.values, c.values) > 0.2) ++told_apart_in_samples;
    }
    CHECK(told_apart_in_samples == 3);
}
