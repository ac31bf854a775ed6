// Where identification before the roll ends cuts its prefixes: on the
// contact's own clock (series/contact_clock.hpp), as the paper's timing rule
// asks: from the half-way rise of the first bump of a touched sensor, never
// from record_start, and in units of that bump's width, never in samples or
// seconds. The clock is read causally, as a live run reads it; a contact that
// begins later, presses harder or crosses more slowly gives the same prefix rows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "analysis/learn/prefix_evaluation.hpp"
#include "analysis/series/contact_clock.hpp"
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

series::ContactClock clock_of(const TrialData& t, std::size_t prefix = 0) {
    series::SeriesSettings s;
    s.prefix = prefix;
    const auto c = series::contact_clock(t, kAll, s);
    REQUIRE(c);
    return *c;
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

bool told_apart(const series::PreparedSeries& a, const series::PreparedSeries& b, double by) {
    return a.ok != b.ok || (a.ok && max_abs_diff(a.values, b.values) > by);
}

}  // namespace

TEST_CASE("the contact's clock: from the first bump's half-way rise, in units of its width", "[series][prefix]") {
    // Channel 0's bump: centre 50 + 0.30 × 80 = 74, sigma 0.08 × 80 = 6.4, so
    // half its height lies ±1.1774 sigma = ±7.54 samples from the centre.
    const TrialData t = make_trial({});
    const auto c = clock_of(t);
    CHECK(c.channel == 0);
    CHECK(c.zero == Approx(74.0 - 7.54).margin(0.3));
    CHECK(c.unit == Approx(2 * 7.54).margin(0.5));
    CHECK(c.known_at == static_cast<std::size_t>(std::ceil(c.zero + c.unit)));

    SECTION("causal: a recording that has just shown the fall finds it; one sample earlier it is not known") {
        const auto live = clock_of(t, c.known_at + 1);
        CHECK(live.zero == c.zero);
        CHECK(live.unit == c.unit);
        series::SeriesSettings s;
        s.prefix = c.known_at;
        CHECK_FALSE(series::contact_clock(t, kAll, s));
    }
    SECTION("scale-free: the same for a contact pressed half as hard") {
        TrialData soft = t;
        for (auto& ch : soft.channels)
            for (double& v : ch) v *= 0.5;
        const auto h = clock_of(soft);
        CHECK(h.zero == Approx(c.zero).margin(1e-9));
        CHECK(h.unit == Approx(c.unit).margin(1e-9));
    }
    SECTION("scale-free: one and a half times as long for a contact 1.5 times as slow") {
        const auto slow = clock_of(make_trial({.stretch = 1.5}));
        CHECK(slow.unit == Approx(1.5 * c.unit).margin(0.5));
        CHECK(slow.zero - 50.0 == Approx(1.5 * (c.zero - 50.0)).margin(0.5));  // the contact starts at 50
    }
    SECTION("a rise under the series rule's touch threshold (min_amplitude) does not start it") {
        TrialData grazed = t;
        for (std::size_t i = 0; i < grazed.samples(); ++i) {
            const double z = (static_cast<double>(i) - 40.0) / 2.0;
            grazed.channels[1][i] += 0.025 * std::exp(-0.5 * z * z);  // a graze 0.025 high, a few samples wide
        }
        const auto g = clock_of(grazed);
        CHECK(g.channel == 0);
        CHECK(g.zero == Approx(c.zero).margin(1e-9));
        // One the rule counts as a touch does: the clock is the rule's.
        series::SeriesSettings touchy;
        touchy.min_amplitude = 0.02;
        const auto on_graze = series::contact_clock(grazed, kAll, touchy);
        REQUIRE(on_graze);
        CHECK(on_graze->channel == 1);
        CHECK(on_graze->zero < 40.0);
    }
    SECTION("scale-free near the threshold: a first bump 0.12 high, pressed 20 % less") {
        TrialData firm = t;
        for (auto& ch : firm.channels)
            for (double& v : ch) v *= 0.12 / 0.45;
        TrialData soft = firm;
        for (auto& ch : soft.channels)
            for (double& v : ch) v *= 0.8;
        const auto a = clock_of(firm), b = clock_of(soft);
        CHECK(b.channel == a.channel);
        CHECK(b.zero == Approx(a.zero).margin(1e-9));
        CHECK(b.unit == Approx(a.unit).margin(1e-9));
    }
    SECTION("a resting level away from zero, with one odd reading among the first three, changes nothing") {
        TrialData raised = t;
        for (auto& ch : raised.channels)
            for (double& v : ch) v += 0.3;
        raised.channels[0][0] = 0.9;
        const auto r = clock_of(raised);
        CHECK(r.zero == Approx(c.zero).margin(1e-9));
        CHECK(r.unit == Approx(c.unit).margin(1e-9));
    }
    SECTION("a reading on the half level, as saved (9 digits) or as measured, gives the same clock") {
        TrialData on_half = t;
        const double half = 0.5 * *std::max_element(t.channels[0].begin(), t.channels[0].end());
        on_half.channels[0][c.known_at] = half;  // the fall's sample lands exactly on the level
        TrialData live = on_half;
        live.channels[0][c.known_at] = half * (1.0 - 4e-10);  // the same reading before rounding to 9 digits
        const auto a = clock_of(on_half), b = clock_of(live);
        CHECK(a.known_at == b.known_at);
        CHECK(b.zero == Approx(a.zero).margin(1e-6));
    }
    SECTION("reading noise moves it by a fraction of a sample") {
        const auto noisy = clock_of(make_trial({.noise = 0.005, .seed = 7}));
        CHECK(noisy.zero == Approx(c.zero).margin(0.5));
        CHECK(noisy.unit == Approx(c.unit).margin(0.7));
    }
    SECTION("an invalid sample at either crossing is stepped over") {
        for (std::size_t bad : {static_cast<std::size_t>(std::floor(c.zero)),
                                static_cast<std::size_t>(std::ceil(c.zero)), c.known_at - 1}) {
            INFO("invalid sample " << bad);
            TrialData g = t;
            g.valid[bad] = 0;
            g.channels[0][bad] = std::nan("");
            const auto v = clock_of(g);
            CHECK(v.channel == 0);
            CHECK(v.zero == Approx(c.zero).margin(0.5));
            CHECK(v.unit == Approx(c.unit).margin(1.0));
        }
    }
    SECTION("invalid samples are skipped, not read") {
        TrialData gap = t;
        gap.channels[0][70] = 99.0;
        gap.valid[70] = 0;
        const auto v = clock_of(gap);
        CHECK(v.zero == Approx(c.zero).margin(1e-9));
        CHECK(v.unit == Approx(c.unit).margin(1e-9));
    }
    SECTION("no clock without a touched sensor") {
        TrialData faint = t;
        for (auto& ch : faint.channels)
            for (double& v : ch) v *= 0.05;  // the highest bump rises 0.025: no sensor touched
        series::SeriesSettings s;
        CHECK_FALSE(series::contact_clock(faint, kAll, s));
    }
}

TEST_CASE("a prefix ends where the clock's progress reaches its fraction, never before the clock is known",
          "[series][prefix]") {
    const series::ContactClock c{0, 40.3, 10.0, 52};
    const double units = 6.0;
    CHECK(learn::prefix_samples(0.5, c, units, 200) == 72);   // 40.3 + 30 = 70.3: samples 0..71 reach it
    CHECK(learn::prefix_samples(0.05, c, units, 200) == 53);  // the clock is known at sample 52
    CHECK(learn::prefix_samples(0.99, c, 30.0, 200) == 200);  // never more than the recording has
    CHECK(learn::prefix_samples(1.0, c, units, 200) == 200);  // the whole roll
    CHECK(learn::prefix_samples(1.0, std::nullopt, units, 200) == 200);
    CHECK(learn::prefix_samples(0.5, std::nullopt, units, 200) == 0);  // no clock: nothing to decide on
    // The live side (clock_progress, what clf:contact_progress returns) agrees sample for sample.
    for (double f = 0.2; f < 1.0; f += 0.05) {
        INFO("fraction " << f);
        const std::size_t keep = learn::prefix_samples(f, c, units, 1000);
        CHECK(series::clock_progress(c, units, keep) >= f);
        CHECK(series::clock_progress(c, units, keep - 1) < f);
    }
}

TEST_CASE("the nominal roll is one figure in clock units for every speed", "[series][prefix]") {
    const std::vector<TrialRecord> records{record("a", "10"), record("b", "10"), record("c", "20")};
    const std::vector<TrialData> data{make_trial({.samples = 200}), make_trial({.samples = 220}),
                                      make_trial({.samples = 300})};
    const learn::PrefixCuts cuts = learn::prefix_cuts(records, data, kAll, {});
    const double unit = cuts.clock[0]->unit;
    CHECK(cuts.units == Approx(series::clock_progress(*cuts.clock[1], 1.0, 220)));  // the median of the three
    CHECK(cuts.units == Approx((219.0 - cuts.clock[1]->zero) / unit));
    REQUIRE(cuts.nominal.size() == 2);
    CHECK(cuts.nominal[0].speed == "10");
    CHECK(cuts.nominal[0].trials == 2);
    CHECK(cuts.nominal[1].trials == 1);
    // The same fraction is the same number of units from the zero at both speeds.
    CHECK(cuts.keep(0, 0.4, 200) == cuts.keep(2, 0.4, 300));
}

TEST_CASE("a contact that begins later gives the same prefixes (time runs from the contact)", "[series][prefix]") {
    // In the second roll the object first touches the array 20 samples later,
    // and its recording is 20 samples longer.
    const TrialData early = make_trial({.samples = 200, .contact_start = 50.0});
    const TrialData late = make_trial({.samples = 220, .contact_start = 70.0});
    const std::vector<TrialRecord> records{record("a", "10"), record("b", "10")};
    const learn::PrefixCuts cuts = learn::prefix_cuts(records, {early, late}, kAll, {});
    REQUIRE(cuts.clock[0]);
    REQUIRE(cuts.clock[1]);
    CHECK(cuts.clock[1]->zero == Approx(cuts.clock[0]->zero + 20.0));

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
        // rule before 2026-11-26), the later contact shows less of itself.
        const auto from_start = static_cast<std::size_t>(std::llround(f * 210.0));
        if (told_apart(prefix_of(early, from_start), prefix_of(late, from_start), 1e-3)) ++told_apart_from_start;
    }
    CHECK(told_apart_from_start >= 2);
}

TEST_CASE("a contact that crosses the array more slowly gives the same prefixes (time runs in its unit)",
          "[series][prefix]") {
    // One object's pattern crossing 1.5 times as slowly (a larger or a smaller
    // object at one roll speed).
    const TrialData fast = make_trial({.samples = 200});
    const TrialData slow = make_trial({.samples = 200, .stretch = 1.5});
    const std::vector<TrialRecord> records{record("fast", "10"), record("slow", "10")};
    const learn::PrefixCuts cuts = learn::prefix_cuts(records, {fast, slow}, kAll, {});
    REQUIRE(cuts.clock[0]);
    REQUIRE(cuts.clock[1]);

    int told_apart_in_samples = 0;
    for (double f : {0.3, 0.4, 0.5}) {
        INFO("fraction " << f);
        const std::size_t keep_fast = cuts.keep(0, f, fast.samples());
        const auto a = prefix_of(fast, keep_fast), b = prefix_of(slow, cuts.keep(1, f, slow.samples()));
        REQUIRE(a.ok);
        REQUIRE(b.ok);
        CHECK(max_abs_diff(a.values, b.values) < 0.08);  // whole samples: each cut moves by up to one
        // The same number of samples after the zero instead (a fixed time, the
        // cut of 72f62aa), the slower contact shows less of itself: the
        // crossing speed, hence the size, would be read from the prefix.
        const auto after = static_cast<double>(keep_fast) - cuts.clock[0]->zero;
        const auto same_time = static_cast<std::size_t>(std::llround(cuts.clock[1]->zero + after));
        if (told_apart(a, prefix_of(slow, same_time), 0.2)) ++told_apart_in_samples;
    }
    CHECK(told_apart_in_samples == 3);
}
