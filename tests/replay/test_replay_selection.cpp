// Which recorded trial plays: the script's trial by id or by object/speed/
// repetition, the next in manifest order, or one pinned with call("select").
#include <catch2/catch.hpp>

#include "replay_fixture.hpp"
#include "trial_selection.hpp"

using namespace rollsense;
using namespace rollsense::plugins::replay;

namespace {
// The first channel of the first sample tells which trial played: write each
// trial with its own offset through the sample count (ch1 = index, so use the
// recorded sample count instead).
std::int64_t played_samples(plugins::replay::ReplaySensor& s) {
    auto st = s.invoke("status", {});
    REQUIRE(st.ok());
    return std::get<std::int64_t>(st->at("recorded_samples"));
}
std::string played_id(plugins::replay::ReplaySensor& s) {
    auto st = s.invoke("status", {});
    REQUIRE(st.ok());
    return std::get<std::string>(st->at("trial"));
}
const std::vector<rt::TrialSpec> kTrials = {
    {"C1", "10", 1, 11}, {"C1", "10", 2, 12}, {"C1", "20", 1, 13}, {"S1", "10", 1, 14}, {"S1", "10.0", 2, 15, 31.1, 0, "custom"},
};
}  // namespace

TEST_CASE("select = match plays the script's trial by id, else by object/speed/repetition", "[replay][select]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", kTrials);
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "20", 1)).ok());
    CHECK(played_id(**s) == "C1-v20-r001");
    CHECK(played_samples(**s) == 13);
    // Another id, same fields: found by object/speed/repetition ("10" = "10.0").
    TrialInfo t = rt::script_trial("S1", "10", 2);
    t.id = "my-own-name";
    REQUIRE((*s)->begin_trial(t).ok());
    CHECK(played_id(**s) == "custom");
    // By id alone.
    TrialInfo by_id;
    by_id.id = "C1-v10-r002";
    REQUIRE((*s)->begin_trial(by_id).ok());
    CHECK(played_samples(**s) == 12);

    auto missing = (*s)->begin_trial(rt::script_trial("C1", "10", 51));
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.code() == ErrorCode::not_found);
    INFO(missing.message());
    CHECK(missing.message().find("dataset " + (dir / "ds").string() +
                                 " has no trial for the script's trial 'C1-v10-r051' (object C1, speed 10, "
                                 "repetition 51); it holds 5 trials: C1-v10-r001, C1-v10-r002") == 0);
    CHECK(missing.message().find("--set devices.tactile.params.select=order") != std::string::npos);
}

TEST_CASE("select = order plays the manifest's trials one after the other", "[replay][select]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", kTrials);
    auto s = rt::open_replay(dir / "ds", {{"select", std::string("order")}});
    REQUIRE(s.ok());
    for (const auto& spec : kTrials) {
        REQUIRE((*s)->begin_trial(rt::script_trial("X9", "5", 1)).ok());
        CHECK(played_id(**s) == rt::trial_id(spec));
        REQUIRE((*s)->end_trial().ok());
    }
    auto over = (*s)->begin_trial(rt::script_trial("X9", "5", 1));
    REQUIRE_FALSE(over.ok());
    CHECK(over.message().find("all 5 trials of dataset") == 0);
    CHECK(over.message().find("have been played (select = 'order'); the script began trial 'X9-v5-r001' after them") !=
          std::string::npos);
}

TEST_CASE("call('select') pins the next trial, call('trials') lists them", "[replay][select]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", kTrials);
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());

    auto list = (*s)->invoke("trials", {});
    REQUIRE(list.ok());
    CHECK(std::get<std::int64_t>(list->at("count")) == 5);
    CHECK(std::get<std::vector<std::string>>(list->at("ids"))[4] == "custom");
    CHECK(std::get<std::vector<std::int64_t>>(list->at("samples"))[2] == 13);
    CHECK(std::get<std::int64_t>(list->at("seed")) == 7);

    // By fields, the speed given as a Lua number.
    auto sel = (*s)->invoke("select", {{"object", std::string("S1")}, {"speed", std::int64_t{10}},
                                       {"repetition", 1.0}});
    REQUIRE(sel.ok());
    CHECK(std::get<std::string>(sel->at("id")) == "S1-v10-r001");
    CHECK(std::get<std::int64_t>(sel->at("index")) == 4);
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());  // the pin wins over the script's trial
    CHECK(played_id(**s) == "S1-v10-r001");
    // The pin is used once: the next trial matches again.
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
    CHECK(played_id(**s) == "C1-v10-r001");
    // No argument: the next one in manifest order after the last played.
    sel = (*s)->invoke("select", {});
    REQUIRE(sel.ok());
    CHECK(std::get<std::string>(sel->at("id")) == "C1-v10-r002");
    // By 1-based index and by id.
    CHECK(std::get<std::string>((*s)->invoke("select", {{"index", std::int64_t{3}}})->at("id")) == "C1-v20-r001");
    CHECK(std::get<std::string>((*s)->invoke("select", {{"id", std::string("custom")}})->at("id")) == "custom");

    auto bad = (*s)->invoke("select", {{"colour", std::string("red")}});
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().message == "select: unknown argument 'colour' (known: id, object, speed, repetition, index)");
    auto none = (*s)->invoke("select", {{"object", std::string("H2")}});
    REQUIRE_FALSE(none.ok());
    CHECK(none.error().message.find("has no object H2; it holds 5 trials") != std::string::npos);
    auto frac = (*s)->invoke("select", {{"repetition", 1.5}});
    REQUIRE_FALSE(frac.ok());
    CHECK(frac.error().message == "select: 'repetition' must be a whole number, not 1.5");
    CHECK((*s)->invoke("rewind", {}).error().code == ErrorCode::unsupported);
}

TEST_CASE("speeds match as labels or as numbers", "[replay][select]") {
    CHECK(same_speed("10", "10"));
    CHECK(same_speed("10", "10.0"));
    CHECK(same_speed("2.5", "2.50"));
    CHECK_FALSE(same_speed("10", "15"));
    CHECK_FALSE(same_speed("fast", "slow"));
}

TEST_CASE("a trial file is read when its trial begins, and dropped when it ends", "[replay][streaming]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 20}, {"C1", "10", 2, 20}});
    auto s = rt::open_replay(dir / "ds");
    REQUIRE(s.ok());
    // Break trial 2 after configure: trial 1 still plays (nothing was read
    // ahead), trial 2 fails when it begins, naming the place.
    rt::write_file(dir / "ds/trials/C1-v10-r002.csv",
                   "time,ch1,ch2,ch3,sensing_finger,valid\n0,1,2,3,4,1\n0.032154,1,oops,3,4,1\n");
    REQUIRE((*s)->begin_trial(rt::script_trial("C1", "10", 1)).ok());
    CHECK(rt::Driver{}.record(**s, 20).back().valid);
    REQUIRE((*s)->end_trial().ok());
    auto st = (*s)->invoke("status", {});
    REQUIRE(st.ok());
    CHECK(st->count("trial") == 0);  // nothing held between trials
    CHECK(std::get<std::int64_t>(st->at("trials_played")) == 1);
    auto bad = (*s)->begin_trial(rt::script_trial("C1", "10", 2));
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.message() == "trial 'C1-v10-r002': " + (dir / "ds/trials/C1-v10-r002.csv").string() +
                               ":3: column 'ch2': 'oops' is not a number");
}
