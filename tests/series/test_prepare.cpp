// The series preparation rule on synthetic trials: its invariances
// (metamorphic: change the trial in a way the rule must ignore, compare) and
// its refusals.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/series/prepare.hpp"
#include "synthetic.hpp"

using namespace rollsense;
using namespace rollsense::series;
using rollsense::testing::make_trial;
using rollsense::testing::SyntheticTrial;

namespace {

const std::vector<std::size_t> kAll{0, 1, 2};

PreparedSeries prepare(const TrialData& t, const SeriesSettings& s = {}) {
    auto r = prepare_series(t, kAll, s);
    REQUIRE(r.ok());
    return *r;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    REQUIRE(a.size() == b.size());
    double d = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

}  // namespace

TEST_CASE("a clean synthetic trial prepares to channels × length values around its contact", "[series]") {
    const auto p = prepare(make_trial({}));
    REQUIRE(p.ok);
    CHECK(p.reason.empty());
    CHECK(p.values.size() == 3 * 128);
    // The first and last bumps cross 10 % of their height 2.15 σ from their
    // centres: at 74 − 13.7 and 106 + 12.0.
    CHECK(p.contact_start == Approx(60.3).margin(0.5));
    CHECK(p.contact_end == Approx(118.0).margin(0.5));
    CHECK(p.window_start < p.contact_start);
    CHECK(p.window_end > p.contact_end);
    // Global scale keeps the amplitudes: channel 2's bump is 0.5 high.
    const double top2 = *std::max_element(p.values.begin() + 128, p.values.begin() + 256);
    CHECK(top2 == Approx(0.5).margin(0.01));
}

TEST_CASE("stretching only the contact in time leaves the prepared series unchanged", "[series][metamorphic]") {
    // The object crossing the array 1.5× slower: more samples inside the
    // contact, the rest of the recording as it was.
    for (double stretch : {1.5, 0.7}) {
        CAPTURE(stretch);
        const auto base = prepare(make_trial({}));
        const auto slow = prepare(make_trial({.stretch = stretch}));
        CHECK(slow.contact_end - slow.contact_start ==
              Approx(stretch * (base.contact_end - base.contact_start)).epsilon(0.02));
        CHECK(max_abs_diff(base.values, slow.values) < 0.01);  // of bumps 0.3–0.5 high

        SeriesSettings z;
        z.amplitude = Amplitude::z_per_channel;
        CHECK(max_abs_diff(prepare(make_trial({}), z).values, prepare(make_trial({.stretch = stretch}), z).values) <
              0.05);  // of unit standard deviation

        // Timing relative to the roll is what the rule forbids: it sees the stretch.
        SeriesSettings roll;
        roll.time_axis = TimeAxis::roll_relative;
        CHECK(max_abs_diff(prepare(make_trial({}), roll).values,
                           prepare(make_trial({.stretch = stretch}), roll).values) > 0.1);
    }
}

TEST_CASE("a trial with one invalid sample prepares and matches the clean one closely", "[series]") {
    const auto clean_trial = make_trial({.noise = 0.005, .seed = 3});
    const auto clean = prepare(clean_trial);

    SECTION("valid = 0") {
        auto t = clean_trial;
        t.valid[90] = 0;
        t.channels[1][90] = 0.0;  // what a failed read leaves behind
        const auto p = prepare(t);
        CHECK(p.ok);
        CHECK(p.invalid_samples == 1);
        CHECK(max_abs_diff(clean.values, p.values) < 0.02);
    }
    SECTION("a NaN reading") {
        auto t = clean_trial;
        t.channels[2][100] = std::numeric_limits<double>::quiet_NaN();
        const auto p = prepare(t);
        CHECK(p.ok);
        CHECK(p.invalid_samples == 1);
        CHECK(max_abs_diff(clean.values, p.values) < 0.02);
        CHECK(std::all_of(p.values.begin(), p.values.end(), [](double v) { return std::isfinite(v); }));
    }
    SECTION("at the first and the last sample") {
        auto t = clean_trial;
        t.valid.front() = 0;
        t.channels[0].back() = std::numeric_limits<double>::infinity();
        const auto p = prepare(t);
        CHECK(p.invalid_samples == 2);
        CHECK(max_abs_diff(clean.values, p.values) < 0.02);
    }
}

TEST_CASE("a constant offset on a channel changes nothing", "[series][metamorphic]") {
    const auto t = make_trial({.noise = 0.005, .seed = 5});
    for (auto amplitude : {Amplitude::global_scale, Amplitude::z_per_channel}) {
        CAPTURE(to_string(amplitude));
        SeriesSettings s;
        s.amplitude = amplitude;
        const auto base = prepare(t, s);
        for (double offset : {0.7, -3.0, 25.0}) {
            CAPTURE(offset);
            auto shifted = t;
            for (double& v : shifted.channels[1]) v += offset;
            const auto p = prepare(shifted, s);
            CHECK(p.contact_start == Approx(base.contact_start).margin(1e-9));
            CHECK(p.contact_end == Approx(base.contact_end).margin(1e-9));
            CHECK(p.baseline[1] == Approx(base.baseline[1] + offset).margin(1e-9));
            CHECK(max_abs_diff(base.values, p.values) <= 1e-12 * std::max(1.0, std::abs(offset)));
        }
    }
}

TEST_CASE("trials the rule cannot use are refused with their reason", "[series]") {
    SECTION("no contact: noise only") {
        auto t = make_trial({.noise = 0.005});
        for (std::size_t c = 0; c < 3; ++c)  // the same noise, without the bumps
            for (std::size_t i = 0; i < t.samples(); ++i)
                t.channels[c][i] -= testing::bumps(c, static_cast<double>(i), 50.0, 80.0);
        const auto p = prepare(t);
        CHECK_FALSE(p.ok);
        CHECK(p.refusal == Refusal::no_contact);
        CHECK(p.reason.rfind("no_contact (largest rise", 0) == 0);
        CHECK(p.values.empty());
    }
    SECTION("every sample invalid") {
        auto t = make_trial({});
        std::fill(t.valid.begin(), t.valid.end(), 0);
        const auto p = prepare(t);
        CHECK(p.refusal == Refusal::too_many_invalid);
        CHECK(p.reason == "too_many_invalid (200 of 200 samples invalid; at most 10% allowed)");
    }
    SECTION("too many scattered invalid samples") {
        auto t = make_trial({});
        for (std::size_t i = 0; i < t.samples(); i += 5) t.valid[i] = 0;  // 20 %
        CHECK(prepare(t).refusal == Refusal::too_many_invalid);
    }
    SECTION("a long run of invalid samples") {
        auto t = make_trial({});
        for (std::size_t i = 80; i < 86; ++i) t.channels[0][i] = std::nan("");
        CHECK(prepare(t).refusal == Refusal::invalid_gap);
        SeriesSettings s;
        s.max_gap = 6;
        CHECK(prepare(t, s).ok);
    }
    SECTION("a contact cut off by the recording") {
        const auto late = make_trial({.samples = 150, .contact_start = 100});  // ends in contact
        CHECK(prepare(late).refusal == Refusal::incomplete_contact);
        const auto early = make_trial({.contact_start = -20});  // starts in contact
        CHECK(prepare(early).refusal == Refusal::incomplete_contact);
        SeriesSettings lax;
        lax.require_complete_contact = false;
        const auto p = prepare(late, lax);
        CHECK(p.ok);
        CHECK(p.window_end == Approx(149.0));  // no margin beyond an open side
    }
    SECTION("too short") {
        auto t = make_trial({});
        SeriesSettings s;
        s.prefix = 5;
        CHECK(prepare(t, s).refusal == Refusal::too_short);
    }
}

TEST_CASE("a prefix: the contact visible so far, and the full length equals no prefix", "[series]") {
    const auto t = make_trial({.noise = 0.005, .seed = 9});
    const auto full = prepare(t);
    SeriesSettings s;
    for (std::size_t prefix : {t.samples(), t.samples() + 50}) {
        s.prefix = prefix;
        const auto p = prepare(t, s);
        CHECK(p.values == full.values);
        CHECK(p.window_end == full.window_end);
    }

    // Mid-contact: the series ends at the prefix's last sample. The start
    // moves a little: thresholds follow the rise seen so far, and the margin
    // the contact's visible length.
    s.prefix = 100;
    const auto mid = prepare(t, s);
    REQUIRE(mid.ok);
    CHECK(mid.contact_start == Approx(full.contact_start).margin(1.0));
    CHECK(mid.window_start < mid.contact_start);
    CHECK(mid.window_start > full.window_start);
    CHECK(mid.window_end == 99.0);
    CHECK(max_abs_diff(mid.values, full.values) > 0.1);
    // Only the samples before the prefix count: changing later ones changes nothing.
    auto later = t;
    for (auto& ch : later.channels)
        for (std::size_t i = 100; i < ch.size(); ++i) ch[i] = 7.0;
    CHECK(prepare(later, s).values == mid.values);

    // Before the contact: nothing to identify yet.
    s.prefix = 40;
    const auto before = prepare(t, s);
    CHECK(before.refusal == Refusal::no_contact);
    CHECK(before.reason.find("within the prefix") != std::string::npos);
}

TEST_CASE("open_end: a recording still going is prepared as the prefix of the same length", "[series]") {
    const auto t = make_trial({.noise = 0.005, .seed = 9});
    // The recording so far, 100 samples, the contact still running at its end.
    auto so_far = t;
    so_far.time.resize(100);
    so_far.valid.resize(100);
    for (auto& ch : so_far.channels) ch.resize(100);
    const auto closed = prepare(so_far);
    CHECK(closed.refusal == Refusal::incomplete_contact);  // a finished recording may not end mid-contact
    SeriesSettings live;
    live.open_end = true;
    const auto open = prepare(so_far, live);
    REQUIRE(open.ok);
    SeriesSettings prefix;
    prefix.prefix = 100;
    CHECK(open.values == prepare(t, prefix).values);  // what the prefix models were trained on
}

TEST_CASE("roll_relative resamples the whole recording, and differs from the contact rule", "[series]") {
    const auto t = make_trial({});
    SeriesSettings roll;
    roll.time_axis = TimeAxis::roll_relative;
    const auto r = prepare(t, roll);
    const auto c = prepare(t);
    CHECK(max_abs_diff(r.values, c.values) > 0.1);
    // Same contact, same baseline; only the time axis differs.
    CHECK(r.contact_start == c.contact_start);
    CHECK(r.baseline == c.baseline);
    CHECK(r.values[0] == Approx(0.0).margin(1e-6));  // the first sample of the recording, at rest
}

TEST_CASE("z_per_channel gives each channel mean 0 and standard deviation 1", "[series]") {
    SeriesSettings s;
    s.amplitude = Amplitude::z_per_channel;
    const auto p = prepare(make_trial({.noise = 0.005}), s);
    for (std::size_t c = 0; c < 3; ++c) {
        double mean = 0.0, sq = 0.0;
        for (std::size_t j = 0; j < 128; ++j) mean += p.values[c * 128 + j];
        mean /= 128;
        for (std::size_t j = 0; j < 128; ++j) sq += (p.values[c * 128 + j] - mean) * (p.values[c * 128 + j] - mean);
        CHECK(mean == Approx(0.0).margin(1e-12));
        CHECK(std::sqrt(sq / 128) == Approx(1.0));
    }
    // A flat, untouched channel is not blown up into unit-variance noise.
    auto flat = make_trial({.noise = 0.001});
    for (std::size_t i = 0; i < flat.samples(); ++i) flat.channels[2][i] = 0.001 * std::sin(static_cast<double>(i));
    const auto f = prepare(flat, s);
    const double top = *std::max_element(f.values.begin() + 256, f.values.end());
    CHECK(top < 0.2);
}

TEST_CASE("length and channel choice shape the row", "[series]") {
    SeriesSettings s;
    s.length = 64;
    const std::vector<std::size_t> two{2, 0};
    auto r = prepare_series(make_trial({}), two, s);
    REQUIRE(r.ok());
    REQUIRE(r->values.size() == 128);
    const auto all = prepare(make_trial({}), s);
    CHECK(std::equal(r->values.begin(), r->values.begin() + 64, all.values.begin() + 128));
}

TEST_CASE("structural problems are errors naming the problem", "[series]") {
    const auto t = make_trial({});
    SECTION("channel index") {
        const std::vector<std::size_t> bad{0, 3};
        auto r = prepare_series(t, bad, {});
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().message == "prepare_series: channel index 3 out of range (the trial has 3 channels)");
        CHECK_FALSE(prepare_series(t, std::vector<std::size_t>{}, {}).ok());
    }
    SECTION("lengths") {
        auto u = t;
        u.channels[1].pop_back();
        auto r = prepare_series(u, kAll, {});
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().message.find("channel index 1 has 199 samples") != std::string::npos);
    }
    SECTION("settings") {
        SeriesSettings s;
        s.length = 1;
        auto r = prepare_series(t, kAll, s);
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().code == ErrorCode::invalid_argument);
        CHECK(r.error().message == "series settings: length 1 must be at least 2");
        s = {};
        s.contact_fraction = 1.5;
        CHECK_FALSE(validate(s).ok());
        s = {};
        s.scale = 0;
        CHECK_FALSE(validate(s).ok());
    }
}
