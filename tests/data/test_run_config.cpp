// run-config.csv: written with the dataset, read back, compared key by key;
// DatasetWriter::open in resume mode refuses another configuration and drops
// a listed trial whose file is cut short.
#include <catch2/catch.hpp>

#include <fstream>

#include "rollsense/dataset.hpp"
#include "rollsense/run_config.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::testing::TempDir;

namespace {
DatasetInfo info_with(RunConfig config) {
    DatasetInfo info;
    info.channels = {"ch1"};
    info.profile = "sim";
    info.seed = 5;
    info.run_config = std::move(config);
    return info;
}
TrialData samples(std::size_t n) {
    TrialData d;
    for (std::size_t i = 0; i < n; ++i) {
        d.time.push_back(0.1 * static_cast<double>(i));
        d.valid.push_back(1);
    }
    d.channels.push_back(std::vector<double>(n, 1.5));
    return d;
}
TrialRecord record(const std::string& object) {
    TrialRecord r;
    r.info.id = object + "-v10-r001";
    r.info.object = object;
    r.info.speed = "10";
    r.info.repetition = 1;
    return r;
}
}  // namespace

TEST_CASE("run-config.csv round-trips, and its differences name each key with both values", "[run_config]") {
    TempDir dir("rollsense-run-config");
    const RunConfig config{{"script", "a.lua"}, {"seed", "5"}, {"set.objects", "C1, C2"}};
    {
        auto w = DatasetWriter::open(dir.path(), info_with(config), DatasetOpenMode::create);
        REQUIRE(w.ok());
    }
    auto back = read_run_config(dir.path());
    REQUIRE(back.ok());
    CHECK(*back == config);
    CHECK(run_config_differences(config, *back).empty());
    const RunConfig other{{"script", "a.lua"}, {"seed", "6"}, {"set.runs", "2"}};
    CHECK(run_config_differences(config, other) ==
          std::vector<std::string>{"seed: recorded '5', this run '6'", "set.objects: recorded 'C1, C2', this run (not given)",
                                   "set.runs: recorded (not given), this run '2'"});
    // Independent review, hw item 11: the same profile file named by another path
    // ("./hand.lua", then "/lab/hand.lua") refused the resume; another file does not.
    const RunConfig here{{"profile", "./hand.lua"}, {"profile_fnv1a", "1f"}}, there{{"profile", "/lab/hand.lua"}, {"profile_fnv1a", "1f"}};
    CHECK(run_config_differences(here, there).empty());
    const RunConfig changed{{"profile", "/lab/hand.lua"}, {"profile_fnv1a", "2e"}};
    CHECK(run_config_differences(here, changed) ==
          std::vector<std::string>{"profile: recorded './hand.lua', this run '/lab/hand.lua'",
                                   "profile_fnv1a: recorded '1f', this run '2e'"});  // another file: not "edited"
    // The same file with other contents was edited (review), and is said to be.
    const RunConfig edited{{"profile", "./hand.lua"}, {"profile_fnv1a", "2e"}};
    CHECK(run_config_differences(here, edited) ==
          std::vector<std::string>{"profile_fnv1a: recorded '1f', this run '2e' (the profile was edited since it "
                                   "recorded: restore it, or record anew into another --out)"});
    // Lua review: an edited module the script requires (or profile the profile includes) was resumed without a word.
    const RunConfig with{{"script", "a.lua"}, {"module.lib.helper_fnv1a", "1f"}, {"include.etroll-joints_fnv1a", "3a"}};
    CHECK(run_config_differences(with, RunConfig{{"script", "a.lua"}, {"module.lib.helper_fnv1a", "2e"},
                                                 {"include.etroll-joints_fnv1a", "4b"}}) ==
          std::vector<std::string>{"include.etroll-joints_fnv1a: recorded '3a', this run '4b' (the included profile "
                                   "etroll-joints was edited since it recorded: restore it, or record anew into another "
                                   "--out)",
                                   "module.lib.helper_fnv1a: recorded '1f', this run '2e' (the module lib.helper was "
                                   "edited since it recorded: restore it, or record anew into another --out)"});
    // A dataset recorded before these rows existed resumes; one whose module is no longer found does not, nor one
    // that lists modules but not this one (diff review: a pcall(require) that had failed then).
    CHECK(run_config_differences(RunConfig{{"script", "a.lua"}}, with).empty());
    CHECK(run_config_differences(RunConfig{{"script", "a.lua"}, {"include.etroll-joints_fnv1a", "3a"}}, with) ==
          std::vector<std::string>{"module.lib.helper_fnv1a: recorded (not given), this run '1f'"});
    CHECK(run_config_differences(with, RunConfig{{"script", "a.lua"}, {"include.etroll-joints_fnv1a", "3a"}}) ==
          std::vector<std::string>{"module.lib.helper_fnv1a: recorded '1f', this run (not given)"});
    auto none = read_run_config(dir / "nowhere");
    REQUIRE(none.ok());
    CHECK(none->empty());
}

// Review (bad inputs): an empty run-config.csv refused the resume naming the
// file but no way out.
TEST_CASE("a resume refused for an empty or damaged run-config.csv names the way on", "[run_config]") {
    TempDir dir("rollsense-run-config-damaged");
    for (const char* text : {"", "key,value\nscript\n"}) {
        INFO(text);
        rollsense::testing::write_file(dir / kRunConfigFile, text);
        const auto s = check_resume_config(dir.path(), RunConfig{{"script", "a.lua"}});
        REQUIRE_FALSE(s.ok());
        CHECK(s.code() == ErrorCode::parse_error);
        CHECK_THAT(s.message(), Catch::StartsWith("cannot resume: ") && Catch::Contains("run-config.csv:") &&
                                    Catch::EndsWith("; repair or restore it (run-info.csv's command_line shows the run "
                                                    "that recorded the dataset), or record anew into another --out"));
    }
}

TEST_CASE("resume refuses another run configuration and records a cut-short trial again", "[run_config]") {
    TempDir dir("rollsense-run-config");
    const RunConfig config{{"script", "a.lua"}, {"set.runs", "3"}};
    {
        auto w = DatasetWriter::open(dir.path(), info_with(config), DatasetOpenMode::create);
        REQUIRE(w.ok());
        REQUIRE((*w)->add_trial(record("C1"), samples(20)).ok());
        REQUIRE((*w)->add_trial(record("C2"), samples(20)).ok());
        REQUIRE((*w)->flush().ok());
    }
    auto refused = DatasetWriter::open(dir.path(), info_with({{"script", "a.lua"}, {"set.runs", "4"}}),
                                       DatasetOpenMode::resume);
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().message, Catch::Contains("set.runs: recorded '3', this run '4'"));

    const auto file = dir / "trials" / "C2-v10-r001.csv";
    const auto text = rollsense::testing::read_file(file);
    rollsense::testing::write_file(file, text.substr(0, text.size() - 20));
    auto resumed = DatasetWriter::open(dir.path(), info_with(config), DatasetOpenMode::resume);
    REQUIRE(resumed.ok());
    CHECK((*resumed)->has_trial("C1-v10-r001"));
    CHECK_FALSE((*resumed)->has_trial("C2-v10-r001"));  // recorded again by the run
}

// Diff review: a dataset recorded before the module and include rows existed was resumed (as it should), but its
// run-config.csv was rewritten with today's digests, which then described the trials recorded earlier too.
TEST_CASE("a resumed dataset recorded before the module rows keeps none, one that lists them keeps today's",
          "[run_config]") {
    const RunConfig old_config{{"script", "a.lua"}, {"set.runs", "3"}};
    const RunConfig now{{"script", "a.lua"}, {"module.etroll_fnv1a", "1f"}, {"set.runs", "3"}};
    for (const bool listed_before : {false, true}) {
        INFO(listed_before);
        TempDir dir("rollsense-run-config-rows");
        {
            auto w = DatasetWriter::open(dir.path(), info_with(listed_before ? now : old_config), DatasetOpenMode::create);
            REQUIRE(w.ok());
            REQUIRE((*w)->add_trial(record("C1"), samples(20)).ok());
            REQUIRE((*w)->flush().ok());
        }
        auto resumed = DatasetWriter::open(dir.path(), info_with(now), DatasetOpenMode::resume);
        REQUIRE(resumed.ok());
        REQUIRE((*resumed)->add_trial(record("C2"), samples(20)).ok());
        REQUIRE((*resumed)->flush().ok());
        const auto written = read_run_config(dir.path());
        REQUIRE(written.ok());
        CHECK(*written == (listed_before ? now : old_config));
    }
}

TEST_CASE("a run killed before its end is known by run-config.csv without run-info.csv", "[run_config]") {
    TempDir dir;
    const auto touch = [&](const char* name) { std::ofstream(dir.path() / name) << "key,value\n"; };
    CHECK_FALSE(run_killed_before_end(dir.path()));  // no run's folder at all
    touch(kRunConfigFile);                           // written as the run starts
    CHECK(run_killed_before_end(dir.path()));
    touch(kRunInfoFile);  // written as a whole run ends (a shard's run: as it starts)
    CHECK_FALSE(run_killed_before_end(dir.path()));
    CHECK_FALSE(run_killed_before_end(dir.path() / "no-such-folder"));
}
