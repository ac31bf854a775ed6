// Issue 22 item 12: a 300-character trial id was accepted by save_trial, then
// its file could not be created (ENAMETOOLONG) and the whole batch, five
// *other* trials with it, was lost; the run's summary still counted them.
// Trial ids are now checked before anything is written, and a failed batch
// write names the trials it lost and counts only the durable ones.
#include <catch2/catch.hpp>

#include <fstream>

#include "rollsense/dataset.hpp"
#include "rollsense/trial_id.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"
#include "tiny_dataset.hpp"

using namespace rollsense;
using rollsense::testing::TempDir;
using rollsense::testing::tiny_info;
using rollsense::testing::tiny_record;
using rollsense::testing::tiny_samples;

TEST_CASE("trial ids that cannot name a file everywhere are refused with the rule they break", "[data][trial_id]") {
    for (const char* good : {"C1-v10-r001", "a", "x.y_z-1", "CONSOLE", "com10", "LPT0"})
        CHECK(check_trial_id(good).ok());
    CHECK(check_trial_id(std::string(kMaxTrialIdLength, 'x')).ok());
    struct Case {
        std::string id;
        std::string says;
    };
    const Case cases[] = {
        {"", "must not be empty"},
        {std::string(kMaxTrialIdLength + 1, 'x'), "101 characters long, more than 100"},
        {std::string(300, 'x'), "300 characters long"},
        {"a/b", "contains '/' at position 2"},
        {"..", "starts with '.'"},
        {".hidden", "starts with '.'"},
        {"a b", "contains 0x20 at position 2"},
        {"a\nb", "contains 0x0A"},
        {"C1,v10", "contains ','"},
        {"caf\xC3\xA9", "contains 0xC3"},
        {"CON", "reserved on Windows"},
        {"nul.csv", "reserved on Windows"},
        {"Com3", "reserved on Windows"},
    };
    for (const auto& c : cases) {
        const auto s = check_trial_id(c.id);
        INFO(c.id);
        REQUIRE_FALSE(s.ok());
        CHECK(s.code() == ErrorCode::invalid_argument);
        CHECK_THAT(s.message(), Catch::Contains(c.says) && Catch::Contains("A-Z a-z 0-9 . _ -"));
    }
}

TEST_CASE("an over-long trial id is refused at add_trial and the rest of its batch is saved", "[data][trial_id]") {
    TempDir dir;
    {
        auto w = DatasetWriter::open(dir / "ds", tiny_info(), DatasetOpenMode::create);
        REQUIRE(w.ok());
        (*w)->set_commit_every(6);
        for (int i = 0; i < 3; ++i) REQUIRE((*w)->add_trial(tiny_record("t" + std::to_string(i)), tiny_samples()).ok());
        const auto bad = (*w)->add_trial(tiny_record(std::string(300, 'x')), tiny_samples());
        REQUIRE_FALSE(bad.ok());
        CHECK_THAT(bad.message(), Catch::Contains("300 characters long"));
        for (int i = 3; i < 5; ++i) REQUIRE((*w)->add_trial(tiny_record("t" + std::to_string(i)), tiny_samples()).ok());
        REQUIRE((*w)->flush().ok());
        CHECK((*w)->durable_trials() == 5);
    }
    auto back = DatasetReader::open(dir / "ds");
    REQUIRE(back.ok());
    CHECK(back->trials().size() == 5);
}

TEST_CASE("a failed batch write names every trial it lost and counts only durable ones", "[data][trial_id]") {
    TempDir dir;
    auto w = DatasetWriter::open(dir / "ds", tiny_info(), DatasetOpenMode::create);
    REQUIRE(w.ok());
    // A non-empty folder where t1's file belongs: the rename onto it fails,
    // as ENOSPC or EIO would, whoever runs the test.
    std::filesystem::create_directories(dir / "ds" / "trials" / "t1.csv" / "blocker");

    SECTION("the failing batch") {
        (*w)->set_commit_every(3);
        for (int i = 0; i < 3; ++i) REQUIRE((*w)->add_trial(tiny_record("t" + std::to_string(i)), tiny_samples()).ok());
        const auto s = (*w)->flush();
        REQUIRE_FALSE(s.ok());
        CHECK_THAT(s.message(), Catch::Contains("3 trial(s) not saved: t0, t1, t2") &&
                                    Catch::Contains("0 trial(s) are safely in"));
        // The way on is the command's: `rollsense run` prints its resume command (one home for that hint).
        CHECK_THAT(s.message(), !Catch::Contains("--resume"));
        CHECK((*w)->durable_trials() == 0);
        CHECK((*w)->lost_trials() == 3);
    }
    SECTION("batches before it stay, batches after it are named") {
        (*w)->set_commit_every(1);
        REQUIRE((*w)->add_trial(tiny_record("t0"), tiny_samples()).ok());
        REQUIRE((*w)->flush().ok());
        (void)(*w)->add_trial(tiny_record("t1"), tiny_samples());  // fails in the background
        (void)(*w)->flush();
        const auto later = (*w)->add_trial(tiny_record("t2"), tiny_samples());
        REQUIRE_FALSE(later.ok());  // nothing more is accepted after a failure
        const auto s = (*w)->flush();
        REQUIRE_FALSE(s.ok());
        CHECK_THAT(s.message(), Catch::Contains("1 trial(s) not saved: t1") &&
                                    Catch::Contains("1 trial(s) are safely in"));
        CHECK((*w)->durable_trials() == 1);
        CHECK((*w)->lost_trials() == 1);
    }
    w->reset();
    auto back = DatasetReader::open(dir / "ds");
    REQUIRE(back.ok());
    CHECK(back->trials().size() <= 1);
}

TEST_CASE("rs.trial refuses an over-long id at once, naming the rule", "[data][trial_id][cli]") {
    TempDir dir;
    const auto script = dir / "long_id.lua";
    std::ofstream(script) << "local rs = require \"rollsense\"\nrs.trial{ id = string.rep(\"x\", 300), object = \"C1\" }\n"
                             "rs.log(\"trial accepted\")\n";
    auto r = rollsense::testing::run_rollsense("run " + script.string() + " --no-progress -q --out " +
                                               (dir / "out").string());
    INFO(r.output);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("300 characters long") && !Catch::Contains("trial accepted"));
}

// Review (bad input) item 8: extras the manifest's "key=value;key=value"
// column cannot give back ("a;b=c" read back as two extras) were written.
TEST_CASE("rs.trial refuses extras the manifest cannot give back, naming them", "[data][trial_id][cli]") {
    TrialInfo fine{"t1", "C1", "10", 1, 0, {{"note", "a=b c"}}};
    CHECK(check_trial_info(fine).ok());
    // A protocol key has a column of its own: its value may hold ';' (review: it was refused).
    TrialInfo mounted{"t1", "C1", "10", 1, 0, {{"mount", "rig;2"}, {"index_in_mount", "1"}}};
    CHECK(check_trial_info(mounted).ok());
    for (const auto& [key, value] : {std::pair{"note", "a;b=c"}, std::pair{"a=b", "1"}, std::pair{"x;y", "1"}}) {
        TrialInfo bad{"t1", "C1", "10", 1, 0, {{key, value}}};
        const auto s = check_trial_info(bad);
        INFO(key << " = " << value);
        CHECK_THAT(s.message(), Catch::Contains("extra '" + std::string(key) + "'") &&
                                    Catch::Contains("give a key without '=' or ';' and a value without ';'"));
    }
    TempDir dir;
    const auto script = dir / "extra.lua";
    std::ofstream(script) << "local rs = require \"rollsense\"\nrs.trial{ object = \"C1\", extra = { note = \"a;b=c\" } }\n"
                             "rs.log(\"trial accepted\")\n";
    auto r = rollsense::testing::run_rollsense("run " + script.string() + " --no-progress -q --out " + (dir / "out").string());
    INFO(r.output);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("extra.lua:2:") && Catch::Contains("extra 'note' = 'a;b=c'") &&
                             !Catch::Contains("trial accepted"));
}

// Review (scripting): extra = 5 and keys that are not names were dropped silently, and a table value was written
// into the manifest as 'table: 0x...', different in every process.
TEST_CASE("rs.trial refuses an extra that is not name = text, number or boolean, at its line") {
    for (const auto& [extra, expected] :
         {std::pair{"5", "rs.trial: extra is a number, not a table {name = value}"},
          std::pair{"{ 'x' }", "rs.trial: extra holds a number key with a string value"},
          std::pair{"{ a = {} }", "rs.trial: extra holds a string key with a table value"}}) {
        INFO(extra);
        TempDir dir;
        const auto script = dir / "extra.lua";
        std::ofstream(script) << "local rs = require \"rollsense\"\nrs.trial{ object = \"C1\", extra = " << extra
                              << " }\nrs.log(\"trial accepted\")\n";
        auto r = rollsense::testing::run_rollsense("run " + script.string() + " --no-progress -q --out " +
                                                   (dir / "out").string());
        INFO(r.output);
        CHECK(r.status == 1);
        CHECK_THAT(r.output, Catch::Contains(std::string("extra.lua:2: ") + expected) && !Catch::Contains("trial accepted"));
    }
}
