// Peaks, validity, rejection reasons and the 13 features on synthetic signals
// whose answers follow from their construction.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "feature_fixtures.hpp"
#include "rollsense/features.hpp"

using namespace rollsense::features;

namespace {

using test::triangle;

FeatureSettings unsmoothed() {
    FeatureSettings s;
    s.smoothing_window = 1;  // features of the signal as built
    return s;
}

// ch1: rise 21 / fall 31 at 60; ch2: rise 31 / fall 21 at 90; ch3: 41 / 41 at 120.
// With the 5 % rule: a rise of r keeps floor(0.95 r) samples before the max
// (21 → 19, 31 → 29, 41 → 38), and the 50 % level keeps floor(r / 2)
// (21 → 10, 31 → 15, 41 → 20). No sample sits exactly on a threshold.
std::vector<std::vector<double>> three_triangles() {
    return {triangle(200, 0.3, 60, 21, 31), triangle(200, 0.5, 90, 31, 21), triangle(200, 0.2, 120, 41, 41)};
}

}  // namespace

TEST_CASE("find_peak walks out to 5 % of the maximum", "[peak]") {
    const auto x = triangle(100, 1.0, 50, 31, 21);
    const Peak p = find_peak(x, 0.05);
    CHECK(p.max_index == 50);
    CHECK(p.max == 1.0);
    CHECK(p.first == 21);
    CHECK(p.last == 69);
    CHECK(p.complete());

    // First occurrence of a plateau maximum.
    const std::vector<double> plateau = {0, 0.2, 1, 1, 0.2, 0};
    CHECK(find_peak(plateau, 0.05).max_index == 2);

    // A peak still high at the end is open on that side.
    const std::vector<double> cut = {0, 0.1, 0.5, 1.0, 0.8};
    const Peak c = find_peak(cut, 0.05);
    CHECK(c.closed_start);
    CHECK_FALSE(c.closed_end);
    CHECK(c.first == 1);
    CHECK(c.last == 4);

    CHECK_FALSE(find_peak(std::vector<double>{}, 0.05).complete());
}

TEST_CASE("the 13 features of three known triangles", "[features]") {
    FeatureExtractor fx(unsmoothed());
    const auto tf = fx.extract(three_triangles());
    REQUIRE(tf.ok());
    REQUIRE(tf->clean);
    CHECK(tf->reason.empty());
    const auto& f = tf->values;
    // width ch1 = 19 + 29 = 48, ch2 = 29 + 19 = 48, ch3 = 38 + 38 = 76.
    CHECK(f[0] == Approx(0.3));
    CHECK(f[1] == Approx(0.5));
    CHECK(f[2] == Approx(0.2));
    CHECK(f[3] == Approx(5.0 / 48));   // mid-point 5 samples after the max
    CHECK(f[4] == Approx(-5.0 / 48));  // mid-point 5 samples before the max
    CHECK(f[5] == Approx(0.0).margin(1e-12));
    CHECK(f[6] == Approx(25.0 / 48));  // 50 % from -10 to +15
    CHECK(f[7] == Approx(25.0 / 48));  // from -15 to +10
    CHECK(f[8] == Approx(40.0 / 48));  // from -20 to +20
    CHECK(f[9] == Approx(48.0 / 48));
    CHECK(f[10] == Approx(76.0 / 48));
    CHECK(f[11] == Approx(30.0 / 48));
    CHECK(f[12] == Approx(30.0 / 48));
    CHECK(tf->channels[1].peak.first == 61);
    CHECK(tf->channels[1].peak.last == 109);
    CHECK(tf->channels[0].window == 1);
}

TEST_CASE("features are ratios: a uniform time column or a speed change does not move them", "[features]") {
    FeatureSettings s = unsmoothed();
    s.time_base = TimeBase::timestamps;
    FeatureExtractor fx(s);
    std::vector<double> t(200);
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = 12.5 + static_cast<double>(i) / 31.1;
    const auto a = fx.extract(three_triangles(), t);
    REQUIRE(a.ok());
    FeatureExtractor plain(unsmoothed());
    const auto b = plain.extract(three_triangles());
    for (std::size_t k = 0; k < kFeatureCount; ++k) CHECK(a->values[k] == Approx(b->values[k]));
    // A timestamps time base without a time column is a clear error.
    const auto e = fx.extract(three_triangles());
    REQUIRE_FALSE(e.ok());
    CHECK_THAT(e.error().message, Catch::Contains("time column"));
}

TEST_CASE("sub-sample crossings interpolate to the exact triangle geometry", "[features]") {
    FeatureSettings s = unsmoothed();
    s.interpolate_crossings = true;
    FeatureExtractor fx(s);
    const auto tf = fx.extract(three_triangles());
    REQUIRE(tf.ok());
    REQUIRE(tf->clean);
    // Linear flanks: 5 % is crossed at 0.95·rise before and 0.95·fall after the max.
    const double w2 = 0.95 * 52;
    CHECK(tf->channels[1].width == Approx(w2));
    CHECK(tf->channels[1].half_width == Approx(26.0));
    CHECK(tf->values[4] == Approx(0.95 * (21 - 31) / 2 / w2));
    CHECK(tf->values[10] == Approx(0.95 * 82 / w2));
}

TEST_CASE("half-width rules differ on a double-humped peak", "[features]") {
    // ch2 has a second hump above 50 % inside the same 5 % peak.
    auto ch = three_triangles();
    auto& c2 = ch[1];
    for (long i = 103; i <= 106; ++i) c2[static_cast<std::size_t>(i)] = 0.4;  // 101, 102 dip below 50 %
    FeatureExtractor out(unsmoothed());
    FeatureSettings cs = unsmoothed();
    cs.half_width = HalfWidthRule::contiguous;
    FeatureExtractor cont(cs);
    const auto a = out.extract(ch);
    const auto b = cont.extract(ch);
    REQUIRE(a->clean);
    REQUIRE(b->clean);
    CHECK(a->channels[1].half_width == Approx(106 - 75));  // outermost: up to the hump's end
    CHECK(b->channels[1].half_width == Approx(25.0));      // contiguous: -15 … +10 around the max
}

TEST_CASE("rejection reasons name the channel and why", "[features][rejection]") {
    FeatureExtractor fx(unsmoothed());

    SECTION("no contact: maximum not above 0.01") {
        auto ch = three_triangles();
        for (auto& v : ch[2]) v *= 0.04;  // max 0.008
        const auto tf = fx.extract(ch);
        REQUIRE(tf.ok());
        CHECK_FALSE(tf->clean);
        CHECK(tf->channels[2].rejection == Rejection::low_amplitude);
        CHECK(tf->reason == "ch3 low_amplitude (max 0.008 <= 0.01)");
        CHECK(std::isnan(tf->values[0]));
    }
    SECTION("peak cut off by the end of the recording") {
        auto ch = three_triangles();
        ch[2] = triangle(200, 0.2, 185, 41, 41);
        const auto tf = fx.extract(ch);
        CHECK_FALSE(tf->clean);
        CHECK(tf->channels[2].rejection == Rejection::incomplete_end);
        CHECK_THAT(tf->reason, Catch::StartsWith("ch3 incomplete_end (still"));
    }
    SECTION("peak already under way at the first sample") {
        auto ch = three_triangles();
        ch[0] = triangle(200, 0.3, 3, 21, 31);
        const auto tf = fx.extract(ch);
        CHECK(tf->channels[0].rejection == Rejection::incomplete_start);
        CHECK_THAT(tf->reason, Catch::StartsWith("ch1 incomplete_start"));
    }
    SECTION("incomplete peaks are accepted when the setting is off") {
        FeatureSettings s = unsmoothed();
        s.require_complete_peak = false;
        FeatureExtractor lenient(s);
        auto ch = three_triangles();
        ch[2] = triangle(200, 0.2, 185, 41, 41);
        CHECK(lenient.extract(ch)->clean);
    }
    SECTION("several channels: every reason is kept") {
        auto ch = three_triangles();
        for (auto& v : ch[0]) v = 0.0;
        ch[1][50] = std::numeric_limits<double>::quiet_NaN();
        const auto tf = fx.extract(ch);
        CHECK(tf->channels[0].rejection == Rejection::low_amplitude);
        CHECK(tf->channels[1].rejection == Rejection::not_finite);
        CHECK_THAT(tf->reason, Catch::Contains("ch1 low_amplitude") && Catch::Contains("; ch2 not_finite"));
    }
    SECTION("a one-sample spike has no width") {
        auto ch = three_triangles();
        ch[1].assign(200, 0.0);
        ch[1][90] = 0.5;
        const auto tf = fx.extract(ch);
        CHECK(tf->channels[1].rejection == Rejection::zero_width);
    }
    SECTION("too short to close a peak") {
        const std::vector<std::vector<double>> ch = {{0.0, 1.0}, {0.0, 1.0}, {0.0, 1.0}};
        const auto tf = fx.extract(ch);
        CHECK(tf->channels[0].rejection == Rejection::too_short);
    }
}

TEST_CASE("structural problems are errors, not rejections", "[features]") {
    FeatureExtractor fx;
    auto ch = three_triangles();
    ch.pop_back();
    CHECK_THAT(fx.extract(ch).error().message, Catch::Contains("exactly 3 channels"));
    ch = three_triangles();
    ch[2].resize(150);
    const auto r = fx.extract(ch);
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error().message, Catch::Contains("channel 3 has 150 samples"));
}

TEST_CASE("default settings: MATLAB window per channel, noise below threshold rejected", "[features]") {
    // A light-noise bump per channel; a noise-only channel must be rejected as
    // no contact even though the noise reaches ±0.004 raw.
    std::vector<std::vector<double>> ch(3, std::vector<double>(150));
    std::uint64_t s = 1;
    for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < 150; ++i) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            const double noise = 0.008 * (static_cast<double>(s >> 11) / 9007199254740992.0 - 0.5);
            const double d = (static_cast<double>(i) - 60.0 - 15.0 * static_cast<double>(c)) / 10.0;
            ch[c][i] = 0.5 * std::exp(-0.5 * d * d) + noise;
        }
    FeatureExtractor fx;
    auto tf = fx.extract(ch);
    REQUIRE(tf.ok());
    CHECK(tf->clean);
    for (const auto& c : tf->channels) {
        CHECK(c.window > 5);
        CHECK(c.window < 40);
    }
    CHECK(tf->values[11] > 0.0);  // ch2 peaks after ch1
    for (auto& v : ch[0]) v = 0.004 * std::sin(v * 1000.0);
    tf = fx.extract(ch);
    CHECK(tf->channels[0].rejection == Rejection::low_amplitude);

    // The shared window scope uses one window for all three channels.
    FeatureSettings shared;
    shared.window_scope = WindowScope::shared;
    FeatureExtractor sx(shared);
    auto st = sx.extract(ch);
    CHECK(st->channels[1].window == st->channels[2].window);
}

TEST_CASE("feature settings round-trip through a parameter set", "[features]") {
    FeatureSettings s;
    s.smoothing_factor = 0.1;
    s.window_scope = WindowScope::shared;
    s.half_width = HalfWidthRule::contiguous;
    auto back = feature_settings_from(to_params(s));
    REQUIRE(back.ok());
    CHECK(back->smoothing_factor == 0.1);
    CHECK(back->window_scope == WindowScope::shared);
    CHECK(back->half_width == HalfWidthRule::contiguous);
    auto validated = rollsense::validate_params(feature_settings_schema(), {}, "test");
    REQUIRE(validated.ok());
    CHECK(feature_settings_from(*validated)->peak_fraction == 0.05);
}
