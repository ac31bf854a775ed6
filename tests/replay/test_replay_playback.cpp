// Playback in time: which recorded sample each read serves on the virtual
// clock's grid, at other recording rates, past the end, and the checks that
// warn when the script's roll or seed does not match the recording's.
#include <catch2/catch.hpp>

#include "playback.hpp"
#include "replay_fixture.hpp"

using namespace rollsense;
using rollsense::plugins::replay::Playback;

TEST_CASE("read m on the virtual clock serves recorded sample m", "[replay][playback]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 120}});
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());
    rt::Driver drive;
    for (double t0 : {0.0, 12.5, 3601.123456789}) {  // wherever the recording falls in the run
        drive.t0 = t0;
        REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
        auto frames = drive.record(**s, 121);
        for (std::size_t m = 0; m < 120; ++m) {
            INFO("t0 " << t0 << ", sample " << m);
            REQUIRE(frames[m].valid);
            CHECK(frames[m].values[0] == static_cast<double>(m));
            CHECK(frames[m].values[2] == 200.0 + static_cast<double>(m));
        }
        // Read 121 comes after the recording's 120 samples: invalid, not zero.
        CHECK_FALSE(frames[120].valid);
        CHECK(std::isnan(frames[120].values[0]));
        CHECK(frames[120].reason.find("past the end of the recording of trial 'C1-v10-r001' (120 samples") !=
              std::string::npos);
        REQUIRE((*s)->end_trial().ok());
    }
}

TEST_CASE("past_end = hold serves the last sample after the end", "[replay][playback]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 10}});
    auto s = rt::open_replay(dir / "ds", {{"past_end", std::string("hold")}});
    REQUIRE(s.ok());
    rt::LogCapture log;
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
    auto frames = rt::Driver{}.record(**s, 15);
    for (std::size_t m = 10; m < 15; ++m) {
        CHECK(frames[m].valid);
        CHECK(frames[m].values[0] == 9.0);
    }
    CHECK(log.count("5 reads came after the recording's end (10 samples); they hold the last recorded sample") == 1);
}

TEST_CASE("a recording at another rate is sampled and held on the run clock", "[replay][playback]") {
    rt::TempDir dir;
    SECTION("recorded twice as fast: every other sample") {
        rt::write_dataset(dir / "ds", {{"C1", "10", 1, 100, 62.2}}, 7, 62.2);
        auto s = rt::open_replay(dir / "ds", {{"check_joint", std::string("")}});
        REQUIRE(s.ok());
        REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
        auto frames = rt::Driver{}.record(**s, 50);
        for (std::size_t m = 0; m < 50; ++m) CHECK(frames[m].values[0] == static_cast<double>(2 * m));
        auto st = (*s)->invoke("status", {});
        REQUIRE(st.ok());
        CHECK(std::get<std::int64_t>(st->at("skipped")) == 49);
        CHECK(std::get<std::int64_t>(st->at("served")) == 50);
    }
    SECTION("recorded half as fast: each sample twice") {
        rt::write_dataset(dir / "ds", {{"C1", "10", 1, 20, 15.55}}, 7, 15.55);
        auto s = rt::open_replay(dir / "ds", {{"check_joint", std::string("")}});
        REQUIRE(s.ok());
        REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
        auto frames = rt::Driver{}.record(**s, 41);
        for (std::size_t m = 0; m < 40; ++m) CHECK(frames[m].values[0] == static_cast<double>(m / 2));
        CHECK_FALSE(frames[40].valid);  // 20 samples of 1/15.55 s: over after 40 reads at 31.1 Hz
        auto st = (*s)->invoke("status", {});
        REQUIRE(st.ok());
        CHECK(std::get<std::int64_t>(st->at("repeated")) == 20);
    }
}

TEST_CASE("a hand-made trial's first sample is the playback's zero", "[replay][playback]") {
    rt::TempDir dir;
    rt::write_file(dir / "ds/manifest.csv", "trial_id,file,object,speed,repetition,samples\nt1,trials/t1.csv,C1,10,1,4\n");
    rt::write_file(dir / "ds/trials/t1.csv", "time,ch1,ch2,ch3\n5.0,1,2,3\n5.5,4,5,6\n6.0,7,8,9\n6.5,10,11,12\n");
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
    rt::Driver d;
    d.rate_hz = 4.0;  // reads every 0.25 s: each 0.5 s sample twice
    auto frames = d.record(**s, 9);
    const double expect[] = {1, 1, 4, 4, 7, 7, 10, 10};
    for (std::size_t m = 0; m < 8; ++m) CHECK(frames[m].values[0] == expect[m]);
    CHECK_FALSE(frames[8].valid);
}

TEST_CASE("Playback counts what a recording at another rate did", "[replay][playback]") {
    Playback p({0.0, 0.1, 0.2, 0.3}, 0.1);
    CHECK(p.period() == Approx(0.1));
    CHECK(p.duration() == Approx(0.4));
    p.start(10.0);
    CHECK(p.locate(10.0).index == 0);
    CHECK(p.locate(10.05).index == 0);
    CHECK(p.locate(10.25).index == 2);
    CHECK(p.locate(10.39).index == 3);
    CHECK(p.locate(10.4).past_end);
    CHECK(p.locate(9.0).before_start);
    CHECK(p.repeated() == 1);
    CHECK(p.skipped() == 1);
    CHECK(p.past_end() == 1);
    CHECK(p.distinct_served() == 3);
}

TEST_CASE("recorded invalid and NaN samples replay as invalid frames with the reason", "[replay][playback]") {
    rt::TempDir dir;
    rt::write_file(dir / "ds/manifest.csv", "trial_id,file,object,speed,repetition,samples\nt1,trials/t1.csv,C1,10,1,3\n");
    rt::write_file(dir / "ds/trials/t1.csv", "time,ch1,ch2,ch3,valid\n0,1,2,3,1\n0.1,NaN,5,6,1\n0.2,7,8,9,0\n");
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
    rt::Driver d;
    d.rate_hz = 10;
    auto frames = d.record(**s, 3);
    CHECK(frames[0].valid);
    CHECK_FALSE(frames[1].valid);
    CHECK(frames[1].reason == "sample 2 of trials/t1.csv holds NaN in column 'ch1'");
    CHECK_FALSE(frames[2].valid);
    CHECK(frames[2].reason == "sample 3 of trials/t1.csv was recorded as invalid");
    CHECK(frames[2].values[0] == 7.0);  // the recorded values are kept for whoever looks
}

TEST_CASE("a roll that differs from the recording's is warned about", "[replay][roll]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 40}});
    rt::Driver d;
    SECTION("the same roll: no warning") {
        rt::LogCapture log;
        auto s = rt::open_replay(dir / "ds");
        REQUIRE(s.ok());
        REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
        d.record(**s, 40);
        CHECK(log.lines().empty());
    }
    SECTION("3 deg off: one warning naming the trial, a summary, frames still valid") {
        rt::LogCapture log;
        auto s = rt::open_replay(dir / "ds");
        REQUIRE(s.ok());
        REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
        auto frames = d.record(**s, 40, [](std::size_t m) { return rt::sweep_angle(m) + (m >= 30 ? 3.0 : 0.0); });
        INFO(log.all());
        CHECK(log.count("trial 'C1-v10-r001'") == 2);
        CHECK(log.count("the script's roll does not match the recording's: sensing_finger at -26.000, the recording "
                        "had -29.000 (tolerance 2.000)") == 1);
        CHECK(log.count("differed from the recording at 10 samples (up to 3.000)") == 1);
        for (const auto& f : frames) CHECK(f.valid);
        auto st = (*s)->invoke("status", {});
        REQUIRE(st.ok());
        CHECK(std::get<std::int64_t>(st->at("roll_mismatches")) == 10);
    }
    SECTION("on_mismatch = invalid marks those frames invalid") {
        auto s = rt::open_replay(dir / "ds", {{"on_mismatch", std::string("invalid")}});
        REQUIRE(s.ok());
        REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
        auto frames = d.record(**s, 40, [](std::size_t m) { return rt::sweep_angle(m) + (m >= 30 ? 3.0 : 0.0); });
        for (std::size_t m = 0; m < 40; ++m) {
            CHECK(frames[m].valid == (m < 30));
            if (m >= 30) CHECK(frames[m].reason.find("roll does not match the recording") == 0);
        }
    }
    SECTION("a tolerance wider than the difference: no warning") {
        rt::LogCapture log;
        auto s = rt::open_replay(dir / "ds", {{"angle_tolerance", 5.0}});
        REQUIRE(s.ok());
        REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
        d.record(**s, 40, [](std::size_t m) { return rt::sweep_angle(m) + 3.0; });
        CHECK(log.lines().empty());
    }
}

TEST_CASE("a run with another seed than the recording's is warned about once", "[replay][roll]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 20, 31.1, 1111}, {"C1", "10", 2, 20, 31.1, 2222}});
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());
    rt::LogCapture log;
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1, 1111)).ok());  // same seed
    REQUIRE((*s)->end_trial().ok());
    CHECK(log.lines().empty());
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 2, 9999)).ok());
    REQUIRE((*s)->end_trial().ok());
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 2, 9999)).ok());
    CHECK(log.count("trial 'C1-v10-r002' was recorded in a run with another --seed (the dataset's run seed is 7)") == 1);
    CHECK(log.count("rerun with --seed 7") == 1);
    auto st = (*s)->invoke("status", {});
    REQUIRE(st.ok());
    CHECK(std::get<std::int64_t>(st->at("seed_mismatches")) == 2);
}

TEST_CASE("stopping before the recording's end is reported", "[replay][playback]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 40}});
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());
    rt::LogCapture log;
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
    rt::Driver{}.record(**s, 25);
    CHECK(log.count("trial 'C1-v10-r001': recording stopped after 25 of 40 recorded samples") == 1);
}
