// The way on that `rollsense run` prints after a failure is one that helps:
// a run whose analysis failed after recording every trial is pointed at the
// commands that analyse the trials on disk (a --resume would run the same
// analysis on the same trials again); a resume that failed before its script
// reached the trials on disk counts them and still offers to resume.
#include <catch2/catch.hpp>

#include "cli_helpers.hpp"

namespace {
using namespace rollsense::testing;
namespace fs = std::filesystem;

const std::string kPaper = shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "paper_experiment.lua");
// Four trials (2 objects x 1 speed x 2 runs): too few for the script's 5-fold analysis (refused before the first
// trial unless analyse=false).
const std::string kFour = " --set runs=2 --set objects=C1,P2 --set speeds=10 --seed 5 --no-progress";
// Six trials, then an analysis in 5 folds whose nested CV tunes on an outer fold's 4 training trials, too few for its
// own 5 folds: it fails after the recording. (The stock script refuses this before its first trial.)
const std::string kSixThenOptimize = R"(local rs = require "rollsense"
local etroll = require "etroll"
for repetition = 1, 3 do
  for _, object in ipairs{ "C1", "P2" } do
    local trial = { object = object, speed = 10, repetition = repetition }
    if not rs.has_trial(rs.trial_id(trial)) then etroll.run_trial(trial) end
  end
end
rs.analyse{ folds = 5, optimize = true }
)";
const std::string kSeed = " --seed 5 --no-progress";

std::size_t manifest_rows(const fs::path& dataset) { return count_of(read_file(dataset / "manifest.csv"), "\n") - 1; }
}  // namespace

// Review (cli item 1): the failed analysis printed `continue with: ... --resume`,
// which recorded nothing and failed the same way again.
TEST_CASE("a run whose analysis fails after its trials are recorded points at the analysis commands, not --resume") {
    TempDir dir("rollsense-cli-way-on");
    const auto out = dir / "out";
    const auto script = shell_quoted(dir / "six.lua");
    write_file(dir / "six.lua", kSixThenOptimize);
    const auto failed = run_rollsense("run " + script + kSeed + " --out " + shell_quoted(out));
    INFO(failed.output);
    REQUIRE(failed.status == 1);
    CHECK(count_of(failed.output, "5 folds need at least 5 trials") == 1);
    CHECK(failed.output.find("failed: 6 trials saved, 0 already on disk") != std::string::npos);
    CHECK(failed.output.find("continue with:") == std::string::npos);
    CHECK(failed.output.find("the analysis failed, not the recording: the 6 trials of " + out.string() +
                             " are on disk (--resume would run the same analysis on them again)") != std::string::npos);
    const std::string commands = "analyse them with: rollsense report " + out.string() + "; rollsense train " +
                                 out.string() + " -o " + (out / "model.rsm").string() + " (";
    CHECK(failed.output.find(commands) != std::string::npos);
    REQUIRE(manifest_rows(out) == 6);

    // What the message says: a resume runs the same analysis on the same trials and fails again ...
    const auto resumed = run_rollsense("run " + script + kSeed + " -q --resume --out " + shell_quoted(out));
    INFO(resumed.output);
    CHECK(resumed.status == 1);
    CHECK(count_of(resumed.output, "5 folds need at least 5 trials") == 1);
    CHECK(resumed.output.find("failed: 0 trials saved, 6 already on disk") != std::string::npos);
    CHECK(resumed.output.find("continue with:") == std::string::npos);
    // ... and the printed commands, with an option that fits the dataset, analyse it.
    const auto report = run_rollsense("report " + shell_quoted(out) + " --folds 2 --repeats 2");
    INFO(report.output);
    CHECK(report.status == 0);
    CHECK(fs::exists(out / "report.html"));
    CHECK(fs::exists(out / "evaluation.json"));
    const auto train = run_rollsense("train " + shell_quoted(out) + " -o " + shell_quoted(out / "model.rsm"));
    INFO(train.output);
    CHECK(train.status == 0);
    CHECK(fs::exists(out / "model.rsm"));
}

// User review (hardware path) item 3: a run of 3 trials (--set runs=1 --set objects=C1) recorded them, 37 s in real
// time on the emulated hand, then its analysis refused ("5 folds need at least 5 trials ... give --folds 3 or fewer"),
// an option `run` does not have. The scripts refuse such a run before the first trial, with the ways that work.
TEST_CASE("the stock scripts refuse, before the first trial, fewer trials than the folds they analyse with") {
    TempDir dir("rollsense-cli-way-on-folds");
    const auto out = dir / "out";
    const auto refused = run_rollsense("run " + kPaper + kFour + " --out " + shell_quoted(out));
    INFO(refused.output);
    CHECK(refused.status == 1);
    CHECK(count_of(refused.output, "objects x speeds x runs = 2 x 1 x 2 = 4 trials, fewer than the 5 the analysis at "
                                   "the end needs (5-fold cross-validation): record more (e.g. --set runs=3), or record "
                                   "only: --set analyse=false") == 1);
    CHECK(refused.output.find("failed: 0 trials saved") != std::string::npos);
    CHECK(refused.output.find("continue with:") == std::string::npos);
    CHECK(refused.output.find("the analysis failed") == std::string::npos);
    CHECK_FALSE(fs::exists(out / "manifest.csv"));

    // Both ways out it gives work: record only, or record more.
    const auto only = run_rollsense("run " + kPaper + kFour + " --set analyse=false -q --out " + shell_quoted(dir / "only"));
    INFO(only.output);
    CHECK(only.status == 0);
    CHECK(manifest_rows(dir / "only") == 4);
    const auto more = run_rollsense("run " + kPaper + " --set runs=3 --set objects=C1,P2 --set speeds=10 --seed 5 "
                                    "--no-progress -q --out " + shell_quoted(dir / "more"));
    INFO(more.output);
    CHECK(more.status == 0);
    CHECK(fs::exists(dir / "more" / "evaluation.txt"));
    // One object has nothing to tell apart: refused before the first trial too, not after five.
    const auto one = run_rollsense("run " + kPaper + " --set runs=5 --set objects=C1 --set speeds=10 --no-progress --out " +
                                   shell_quoted(dir / "one"));
    INFO(one.output);
    CHECK(one.status == 1);
    CHECK(count_of(one.output, "objects = C1: the analysis at the end tells objects apart and needs two or more") == 1);
    CHECK(one.output.find("failed: 0 trials saved") != std::string::npos);
    // The objects are said first: one object and too few trials is told to list more objects, not to record more runs.
    const auto both = run_rollsense("run " + kPaper + " --set runs=1 --set objects=C1 --set speeds=10 --no-progress --out " +
                                    shell_quoted(dir / "both"));
    CHECK(count_of(both.output, "needs two or more") == 1);
    CHECK(both.output.find("record more") == std::string::npos);
    // With optimize the nested CV tunes in 5 folds of each outer training part: 6 trials recorded, then failed there.
    const auto tuned = run_rollsense("run " + kPaper + " --set runs=3 --set objects=C1,P2 --set speeds=10 --set "
                                     "optimize=true --no-progress --out " + shell_quoted(dir / "tuned"));
    INFO(tuned.output);
    CHECK(tuned.status == 1);
    CHECK(count_of(tuned.output, "= 6 trials, fewer than the 7 the analysis at the end needs (optimize: 5-fold "
                                 "cross-validation, tuned in 5 folds of each training part): record more (e.g. --set "
                                 "runs=4)") == 1);
    CHECK(tuned.output.find("failed: 0 trials saved") != std::string::npos);
    // An object listed twice is the command line's mistake (second diff review: it recorded, then "3 already on disk").
    const auto twice = run_rollsense("run " + kPaper + " --set runs=3 --set objects=C1,C1 --set speeds=10 --no-progress "
                                     "--out " + shell_quoted(dir / "twice"));
    INFO(twice.output);
    CHECK(twice.status == 2);
    CHECK(count_of(twice.output, "'C1' is listed twice; list each object once") == 1);
    const auto compare_one = run_rollsense("run " + shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" /
                                                                 "compare_methods.lua") +
                                           " --set runs=5 --set objects=C1 --set speeds=10 --no-progress --out " +
                                           shell_quoted(dir / "compare-one"));
    CHECK(compare_one.status == 1);
    CHECK(count_of(compare_one.output, "objects = C1: the comparison tells objects apart and needs two or more") == 1);

    // compare_methods.lua records the same experiment and always compares, with 5 folds.
    const auto compare = run_rollsense("run " + shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "compare_methods.lua") +
                                       " --set runs=1 --set objects=C1,P2 --set speeds=10 --no-progress --out " +
                                       shell_quoted(dir / "compare"));
    INFO(compare.output);
    CHECK(compare.status == 1);
    CHECK(count_of(compare.output, "objects x speeds x runs = 2 x 1 x 1 = 2 trials, fewer than the 5 the comparison "
                                   "needs (5-fold cross-validation): record more (e.g. --set runs=3)") == 1);
    CHECK(compare.output.find("failed: 0 trials saved") != std::string::npos);
}

// Review (cli item 2): the summary said "0 already on disk" of a dataset that held
// every trial, and no way on was printed: the count was of the trials the script
// skipped, and this run failed before its script started.
TEST_CASE("a resume that fails before its script reaches the trials on disk counts them and offers to resume") {
    TempDir dir("rollsense-cli-way-on-resume");
    const std::string small = " --set runs=2 --set objects=C1,P2 --set speeds=10 --set analyse=false --seed 5 --no-progress";
    REQUIRE(run_rollsense("run " + kPaper + small + " -q --out " + shell_quoted(dir / "src")).status == 0);
    const std::string replay = "run " + kPaper + small + " --profile replay --set dataset=" + shell_quoted(dir / "src") +
                               " --out " + shell_quoted(dir / "rep");
    REQUIRE(run_rollsense(replay + " -q").status == 0);
    REQUIRE(manifest_rows(dir / "rep") == 4);
    fs::rename(dir / "src", dir / "moved");  // the replayed dataset is gone: the replay plugin cannot be configured

    const auto failed = run_rollsense(replay + " --resume");
    INFO(failed.output);
    CHECK(failed.status == 3);
    CHECK(failed.output.find("failed: 0 trials saved, 4 already on disk") != std::string::npos);
    CHECK(failed.output.find("results: " + (dir / "rep").string()) != std::string::npos);
    CHECK(failed.output.find("continue with: rollsense run ") != std::string::npos);
    CHECK(failed.output.find("the analysis failed") == std::string::npos);
    CHECK(manifest_rows(dir / "rep") == 4);

    fs::rename(dir / "moved", dir / "src");  // put back, the printed resume finishes the run
    const auto again = run_rollsense(replay + " --resume");
    INFO(again.output);
    CHECK(again.status == 0);
    CHECK(again.output.find("done: 0 trials saved, 4 already on disk") != std::string::npos);
}

// Newcomer review item 4: after a script's own error the printed resume was a
// dead end (the same error again, or, the script fixed, refused as another
// experiment), with nothing saying so.
TEST_CASE("a run a script error stops says that a resume runs the same script, then how to resume") {
    TempDir dir("rollsense-cli-way-on-script");
    write_file(dir / "fails.lua", R"(local rs = require "rollsense"
local etroll = require "etroll"
for r = 1, 3 do
  if r == 3 then error("my bug at trial " .. r) end
  etroll.run_trial{ object = "C1", speed = 10, repetition = r }
end
)");
    const auto failed = run_rollsense("run " + shell_quoted(dir / "fails.lua") + " --no-progress --out " +
                                      shell_quoted(dir / "out"));
    INFO(failed.output);
    CHECK(failed.status == 1);
    CHECK(failed.output.find("fails.lua:4: my bug at trial 3") != std::string::npos);
    CHECK(failed.output.find("failed: 2 trials saved") != std::string::npos);
    const auto note = failed.output.find("a resume runs the same script again and refuses an edited one");
    const auto command = failed.output.find("continue with: rollsense run ");
    CHECK(note != std::string::npos);
    CHECK(command != std::string::npos);
    CHECK(note < command);
}

// Determinism review: the shipped speed sweep, interrupted, printed a resume
// command that failed for ever ("trial 'C3-v5-r001' is already in ..."), with
// no word on how a script skips the trials on disk.
TEST_CASE("the shipped speed sweep resumes, a script that records a trial on disk again is told how to skip it") {
    TempDir dir("rollsense-cli-way-on-sweep");
    const std::string sweep = "run " + shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "examples" / "speed_sweep.lua") +
                              " --seed 2 --no-progress --out " + shell_quoted(dir / "sweep");
    const auto cut = run_rollsense(sweep + " --time-limit 25");
    INFO(cut.output);
    REQUIRE(cut.status == 130);
    // A cancel prints only the way on: the reminder about an edited script is for failures (README, dataset-format.md).
    CHECK(cut.output.find("continue with: rollsense run ") != std::string::npos);
    CHECK(cut.output.find("a resume runs the same script again") == std::string::npos);
    const auto resumed = run_rollsense(sweep + " --resume");
    INFO(resumed.output);
    CHECK(resumed.status == 0);
    CHECK(manifest_rows(dir / "sweep") == 5);  // speeds 5, 10, ..., 25

    write_file(dir / "again.lua", "local rs = require 'rollsense'\nlocal etroll = require 'etroll'\n"
                                  "etroll.run_trial{ object = 'C1', speed = 10, repetition = 1 }\n");
    const std::string again = "run " + shell_quoted(dir / "again.lua") + " --no-progress --out " + shell_quoted(dir / "again");
    REQUIRE(run_rollsense(again).status == 0);
    const auto twice = run_rollsense(again + " --resume");
    INFO(twice.output);
    CHECK(twice.status == 1);
    CHECK(twice.output.find("trial 'C1-v10-r001' is already in ") != std::string::npos);
    CHECK(twice.output.find("skip a recorded trial with 'if not rs.has_trial(id)'") != std::string::npos);
    // Saved twice in one run, no resume: said as such (user review: the resume's advice, for a run that resumed nothing).
    write_file(dir / "twice.lua", "local rs = require 'rollsense'\n"
                                  "rs.trial{ object = 'C1', speed = 10, repetition = 1 }\n"
                                  "rs.record_start() rs.wait(100) rs.record_stop()\nrs.save_trial()\nrs.save_trial()\n");
    const auto in_one_run = run_rollsense("run " + shell_quoted(dir / "twice.lua") + " --no-progress --out " +
                                          shell_quoted(dir / "twice"));
    INFO(in_one_run.output);
    CHECK(in_one_run.status == 1);
    CHECK(count_of(in_one_run.output, "twice.lua:5: trial 'C1-v10-r001' was saved already in this run") == 1);
    CHECK(in_one_run.output.find("rs.has_trial") == std::string::npos);
}

// Review (user journeys) item 3 and (bad input) item 3: the note that a resume
// runs the same script came only after a Lua error, not after an API misuse;
// a resume refused for an edited script named a hash; a refused setup named
// the profile and seed when another key differed, and was followed by the
// same refused command as "continue with".
TEST_CASE("after a script's misuse, an edited script and another setup, the way on is one that works") {
    TempDir dir("rollsense-cli-way-on-misuse");
    const auto script = dir / "twice.lua";
    write_file(script, R"(local rs = require "rollsense"
local etroll = require "etroll"
for r = 1, 2 do etroll.run_trial{ object = "C1", speed = 10, repetition = r } end
rs.record_start()
rs.record_start()
)");
    const auto out = dir / "out";
    const auto failed = run_rollsense("run " + shell_quoted(script) + " --no-progress --out " + shell_quoted(out));
    INFO(failed.output);
    CHECK(failed.status != 0);
    CHECK(failed.output.find("failed: 2 trials saved") != std::string::npos);
    CHECK(failed.output.find("a resume runs the same script again and refuses an edited one") != std::string::npos);
    CHECK(failed.output.find("continue with: rollsense run ") != std::string::npos);

    write_file(script, read_file(script) + "-- fixed\n");
    const auto edited = run_rollsense("run " + shell_quoted(script) + " --no-progress --resume --out " + shell_quoted(out));
    INFO(edited.output);
    CHECK(edited.status == 2);
    CHECK(edited.output.find("the script was edited since it recorded: restore it, or record anew into another --out") !=
          std::string::npos);

    // The recorded sample rate differs from this run's: that key is named, and no resume is offered.
    const std::string info = read_file(out / "dataset-info.csv");
    const auto at = info.find("sample_rate_hz,");
    REQUIRE(at != std::string::npos);
    write_file(out / "dataset-info.csv", info.substr(0, at) + "sample_rate_hz,31.2" + info.substr(info.find('\n', at)));
    write_file(script, read_file(script).substr(0, read_file(script).size() - std::string("-- fixed\n").size()));
    const auto setup = run_rollsense("run " + shell_quoted(script) + " --no-progress --resume --out " + shell_quoted(out));
    INFO(setup.output);
    CHECK(setup.status == 2);
    CHECK(setup.output.find("was recorded with another setup (sample_rate_hz was '31.2', this run's '31.1')") !=
          std::string::npos);
    CHECK(setup.output.find("continue with:") == std::string::npos);
}

// Review (bad input) item 4: an empty run-info.csv refused a resume as a bad
// command line (exit 2) with no way out.
TEST_CASE("a resume refused for an unreadable run-info.csv is the dataset's error and names the way out") {
    TempDir dir("rollsense-cli-way-on-run-info");
    const auto out = dir / "out";
    const std::string run = "run " + kPaper + kFour + " --set analyse=false -q --out " + shell_quoted(out);
    REQUIRE(run_rollsense(run).status == 0);
    write_file(out / "run-info.csv", "");
    const auto refused = run_rollsense(run + " --resume");
    INFO(refused.output);
    CHECK(refused.status == 3);
    CHECK(count_of(refused.output, "run-info.csv:1: the file is empty") == 1);
    CHECK(refused.output.find("move it aside (e.g. to run-info.damaged.csv) and resume again") != std::string::npos);
    fs::rename(out / "run-info.csv", out / "run-info.damaged.csv");
    const auto resumed = run_rollsense(run + " --resume");
    INFO(resumed.output);
    CHECK(resumed.status == 0);
}

// Second review: a script error of over 1 MiB went whole into run-info.csv,
// whose reading then refused the very resume the run had printed.
TEST_CASE("a huge script error is cut in run-info.csv, and the printed resume works") {
    TempDir dir("rollsense-cli-way-on-huge-error");
    write_file(dir / "huge.lua", R"(local rs = require "rollsense"
local etroll = require "etroll"
local function roll(r)
  local t = { object = "C1", speed = 10, repetition = r }
  if not rs.has_trial(rs.trial_id(t)) then etroll.run_trial(t) end
end
roll(1)
if os.getenv("ROLLSENSE_TEST_FAIL") == "1" then error(string.rep("x", 1100000)) end
roll(2)
)");
    const auto out = dir / "out";
    const std::string run = "run " + shell_quoted(dir / "huge.lua") + " --no-progress -q --out " + shell_quoted(out);
    const auto failed = run_command("ROLLSENSE_TEST_FAIL=1 " + rollsense_bin() + " " + run + " 2>&1 | tail -c 2000");
    INFO(failed.output);
    CHECK(failed.output.find("continue with: rollsense run ") != std::string::npos);
    CHECK(fs::file_size(out / "run-info.csv") < 70000);
    const auto resumed = run_rollsense(run + " --resume");
    INFO(resumed.output);
    CHECK(resumed.status == 0);
    CHECK(manifest_rows(out) == 2);
}

// Review (bad input) item 8: a resume refused for a damaged manifest row named
// the line and no way on. Deleting the row is one: the trial is recorded again.
TEST_CASE("a resume refused for a damaged manifest row names the way on, and deleting the row works") {
    TempDir dir("rollsense-cli-way-on-manifest-row");
    const auto out = dir / "out";
    const std::string run = "run " + kPaper + kFour + " --set analyse=false -q --out " + shell_quoted(out);
    REQUIRE(run_rollsense(run).status == 0);
    const std::string manifest = read_file(out / "manifest.csv");
    const auto third = manifest.find('\n', manifest.find('\n', manifest.find('\n') + 1) + 1);  // end of line 3
    const auto second = manifest.rfind('\n', third - 1);                                       // end of line 2
    write_file(out / "manifest.csv", manifest.substr(0, second + 1) + "a,b,c\n" + manifest.substr(third + 1));
    const auto refused = run_rollsense(run + " --resume");
    INFO(refused.output);
    CHECK(refused.status == 3);
    CHECK(count_of(refused.output, "manifest.csv:3: 3 fields") == 1);
    CHECK(refused.output.find("a manifest row may also be deleted: a resume records again a trial it does not list") !=
          std::string::npos);
    write_file(out / "manifest.csv", manifest.substr(0, second + 1) + manifest.substr(third + 1));
    const auto resumed = run_rollsense(run + " --resume");
    INFO(resumed.output);
    CHECK(resumed.status == 0);
    CHECK(read_file(out / "manifest.csv").size() == manifest.size());  // the deleted row's trial, recorded again
}

// Review: a device whose shutdown failed after the script's end (its plugin threw in on_deactivate), or a cleanup
// that failed, was followed by "continue with: ... --resume", which would record nothing. The fault is still reported
// (exit 4: check the device), once.
TEST_CASE("a run that fails after its script's end says its trials are on disk, and offers no resume") {
    TempDir dir("rollsense-cli-after-end");
    write_file(dir / "two.lua", "local rs = require 'rollsense'\nlocal etroll = require 'etroll'\n"
                                "rs.on_cleanup(etroll.park)\n"
                                "for r = 1, 2 do etroll.run_trial{ object = 'C1', speed = 20, repetition = r } end\n");
    write_file(dir / "with-thrower.lua",
               "return { clock = 'virtual', sample_rate_hz = 31.1, control_rate_hz = 100,\n"
               "  devices = { hand = include('mock-hand'), tactile = { plugin = 'sim', params = include('etroll-hand') },\n"
               "              extra = { plugin = 'test_thrower', params = { throw_in = 'deactivate' } } },\n"
               "  joints = include('etroll-joints'), record_joints = { 'sensing_finger' } }\n");
    const auto shutdown = run_command("ROLLSENSE_PLUGIN_PATH=" + shell_quoted(ROLLSENSE_TEST_PLUGIN_DIR) + " " +
                                      ROLLSENSE_BIN_DIR + "/rollsense run " + shell_quoted(dir / "two.lua") +
                                      " --no-progress --profile " + shell_quoted(dir / "with-thrower.lua") + " --out " +
                                      shell_quoted(dir / "a"));
    INFO(shutdown.output);
    CHECK(shutdown.status == 4);
    CHECK(count_of(shutdown.output, "boom in deactivate") == 1);
    CHECK(manifest_rows(dir / "a") == 2);

    write_file(dir / "cleanup.lua", "local rs = require 'rollsense'\nlocal etroll = require 'etroll'\n"
                                    "rs.on_cleanup(function() error('cleanup broke') end)\n"
                                    "for r = 1, 2 do etroll.run_trial{ object = 'C1', speed = 20, repetition = r } end\n");
    const auto cleanup = run_rollsense("run " + shell_quoted(dir / "cleanup.lua") + " --no-progress --out " +
                                       shell_quoted(dir / "b"));
    INFO(cleanup.output);
    CHECK(cleanup.status == 1);
    CHECK(count_of(cleanup.output, "cleanup broke") == 1);
    for (const auto* run : {&shutdown, &cleanup}) {
        CHECK(run->output.find("continue with:") == std::string::npos);
        CHECK(run->output.find("the script ran to its end and its trials are on disk; what failed came after it "
                               "(above): a resume would record nothing") != std::string::npos);
    }
}

// Lua review: a resume after the script's helper module was edited mixed trials of both versions in one dataset
// (run-config.csv held the script's digest only). The modules it requires are listed with theirs now.
TEST_CASE("a resume refuses a script whose required module was edited since the dataset was recorded") {
    TempDir dir("rollsense-cli-module-edit");
    write_file(dir / "lib" / "helper.lua", "return { speed = 20 }\n");
    write_file(dir / "lib" / "old.lua", "return {}\n");
    write_file(dir / "lib" / "guarded.lua", "return {}\n");
    write_file(dir / "two.lua", "local rs = require 'rollsense'\nlocal usage = 'a --[[ in a string is no comment'\n"
                                "local etroll = require 'etroll'\n"
                                "local helper = require('lib.helper')\nrs.on_cleanup(etroll.park)\n"
                                "-- was: local old = require 'lib.old'\n--[==[ require 'lib.old' ]==]\n"
                                "local ok = pcall(require, 'lib.guarded')\n"
                                "for r = 1, 2 do\n  local id = rs.trial_id{ object = 'C1', speed = helper.speed, repetition = r }\n"
                                "  if not rs.has_trial(id) then\n"
                                "    etroll.run_trial{ object = 'C1', speed = helper.speed, repetition = r }\n  end\nend\n");
    const std::string run = "run " + shell_quoted(dir / "two.lua") + " --no-progress --out " + shell_quoted(dir / "out");
    const auto first = run_rollsense(run);
    INFO(first.output);
    REQUIRE(first.status == 0);
    CHECK(read_file(dir / "out" / "run-config.csv").find("\nmodule.lib.helper_fnv1a,") != std::string::npos);
    CHECK(read_file(dir / "out" / "run-config.csv").find("\nmodule.etroll_fnv1a,") != std::string::npos);
    CHECK(read_file(dir / "out" / "run-config.csv").find("\nmodule.lib.guarded_fnv1a,") != std::string::npos);
    // A module named only in a comment is not read: editing it changes nothing (diff review).
    CHECK(read_file(dir / "out" / "run-config.csv").find("lib.old") == std::string::npos);
    write_file(dir / "lib" / "old.lua", "return { edited = true }\n");
    CHECK(run_rollsense(run + " --resume").status == 0);  // unchanged: resumes (nothing left to record)
    write_file(dir / "lib" / "helper.lua", "return { speed = 10 }\n");
    const auto edited = run_rollsense(run + " --resume");
    INFO(edited.output);
    CHECK(edited.status == 2);
    CHECK(count_of(edited.output, "the module lib.helper was edited since it recorded") == 1);
    CHECK(manifest_rows(dir / "out") == 2);
}
