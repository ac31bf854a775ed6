// Control-loop timing statistics (printed after runs on a real clock).
#include <catch2/catch.hpp>

#include "runtime/session/loop_timing.hpp"

using rollsense::runtime::DurationHistogram;
using rollsense::runtime::LoopTiming;

TEST_CASE("duration histogram quantiles are exact to the 10 us bin") {
    DurationHistogram h;
    CHECK(h.quantile(0.5) == 0.0);
    for (int i = 1; i <= 100; ++i) h.add(i * 1e-3);  // 1 ms ... 100 ms
    CHECK(h.count() == 100);
    CHECK(h.quantile(0.5) == Approx(50e-3).margin(10e-6));
    CHECK(h.quantile(0.99) == Approx(99e-3).margin(10e-6));
    CHECK(h.quantile(1.0) == Approx(100e-3).margin(10e-6));
    CHECK(h.max() == Approx(100e-3));
    h.add(3.0);  // beyond the histogram: the overflow bin reports the maximum
    CHECK(h.quantile(1.0) == Approx(3.0));
}

TEST_CASE("loop timing reports period, jitter about the nominal period and busy time") {
    LoopTiming t(0.010);
    for (int i = 0; i < 98; ++i) t.add(0.010, 0.002);
    t.add(0.013, 0.004);  // one late period
    t.add(0.007, 0.002);  // and the short one that catches up
    const auto s = t.summary();
    CHECK(s.periods == 100);
    CHECK(s.period_p50_s == Approx(0.010).margin(10e-6));
    CHECK(s.period_max_s == Approx(0.013));
    CHECK(s.jitter_p50_s == Approx(0.0).margin(10e-6));
    CHECK(s.jitter_p99_s == Approx(0.003).margin(10e-6));
    CHECK(s.busy_p50_s == Approx(0.002).margin(10e-6));
    CHECK_THAT(s.describe(), Catch::Contains("100 Hz over 100 periods") && Catch::Contains("max 13.00 ms"));
}
