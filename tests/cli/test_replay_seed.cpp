// `rollsense run` on the replay profile adopts the recording's seed when no
// --seed is given (issue 24 item 3): the replay of a seed-5 recording then
// reproduces its trials and its features.csv byte for byte. An explicit
// --seed still wins, and the run says which seed it used.
#include <catch2/catch.hpp>

#include "cli_helpers.hpp"

namespace {
using namespace rollsense::testing;
namespace fs = std::filesystem;

const std::string kExperiment = shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "paper_experiment.lua") +
                                " --set runs=3 --set objects=C1,P1 --set speeds=10,20 --no-progress";

std::string dataset_info_value(const fs::path& dir, const std::string& key) {
    const std::string text = read_file(dir / "dataset-info.csv");
    const auto at = text.find("\n" + key + ",");
    if (at == std::string::npos) return {};
    const auto start = at + key.size() + 2;
    return text.substr(start, text.find('\n', start) - start);
}

// Records the experiment at seed 5 on the mock hand into DIR/rec, then
// replays it into DIR/rep with `replay_options`; both must succeed.
CommandRun record_and_replay(const TempDir& dir, const std::string& options, const std::string& replay_options) {
    const auto rec = run_rollsense("run " + kExperiment + options + " --profile mock --seed 5 --out " + shell_quoted(dir / "rec"));
    INFO(rec.output);
    REQUIRE(rec.status == 0);
    const auto rep = run_rollsense("run " + kExperiment + options + " --profile replay --set dataset=" +
                                   shell_quoted(dir / "rec") + replay_options + " --out " + shell_quoted(dir / "rep"));
    INFO(rep.output);
    REQUIRE(rep.status == 0);
    return rep;
}

}  // namespace

TEST_CASE("a replay without --seed adopts the recording's seed and reproduces its features") {
    TempDir dir("rollsense-cli-replay-seed");
    const auto rep = record_and_replay(dir, "", "");
    INFO(rep.output);
    CHECK(rep.output.find("uses the recording's seed 5") != std::string::npos);  // says where the seed came from
    CHECK(rep.output.find("another --seed") == std::string::npos);  // no seed-mismatch warning
    CHECK(dataset_info_value(dir / "rep", "seed") == "5");
    CHECK(read_file(dir / "rep" / "manifest.csv") == read_file(dir / "rec" / "manifest.csv"));
    const std::string features = read_file(dir / "rec" / "features.csv");
    REQUIRE_FALSE(features.empty());
    CHECK(read_file(dir / "rep" / "features.csv") == features);
}

// Determinism review: run-config.csv said seed 1 (the default) for a replay
// that used the recording's seed, so resuming it with that --seed was refused,
// and one started with --seed resumed without it too.
TEST_CASE("a replay's run-config records the seed it used: resumed with or without that --seed, it goes on") {
    TempDir dir("rollsense-cli-replay-seed-resume");
    const auto rep = record_and_replay(dir, " --set analyse=false", "");
    CHECK(read_file(dir / "rep" / "run-config.csv").find("\nseed,5\n") != std::string::npos);
    const std::string replay = "run " + kExperiment + " --set analyse=false --profile replay --set dataset=" +
                               shell_quoted(dir / "rec") + " --out " + shell_quoted(dir / "rep") + " --resume";
    for (const char* seed : {" --seed 5", ""}) {
        const auto again = run_rollsense(replay + seed);
        INFO(again.output);
        CHECK(again.status == 0);
        CHECK(again.output.find("done: 0 trials saved, 12 already on disk") != std::string::npos);
    }
}

TEST_CASE("an explicit --seed overrides the recording's on replay") {
    TempDir dir("rollsense-cli-replay-seed-given");
    const auto rep = record_and_replay(dir, " --set analyse=false", " --seed 11");
    INFO(rep.output);
    CHECK(dataset_info_value(dir / "rep", "seed") == "11");
    CHECK(rep.output.find("rerun with --seed 5") != std::string::npos);  // the replay's own warning
}

// Review: a misspelt check_joint finished "done", the roll check silently off
// (an info line, hidden by -q). Refused before anything runs, naming the --set
// that gave it: a bad command line (exit 2).
TEST_CASE("a replay whose check_joint the recording lacks is refused at configure time") {
    TempDir dir("rollsense-cli-replay-check-joint");
    const std::string small = " --set runs=1 --set objects=C1 --set speeds=10 --set analyse=false -q";
    const auto rec = run_rollsense("run " + kExperiment + small + " --profile mock --seed 5 --out " +
                                   shell_quoted(dir / "rec"));
    REQUIRE(rec.status == 0);
    const auto rep = run_rollsense("run " + kExperiment + small + " --profile replay --set dataset=" +
                                   shell_quoted(dir / "rec") + " --set devices.tactile.params.check_joint=nosuch --out " +
                                   shell_quoted(dir / "rep"));
    INFO(rep.output);
    CHECK(rep.status == 2);
    CHECK(rep.output.find("--set devices.tactile.params.check_joint='nosuch': ") != std::string::npos);
    CHECK(rep.output.find("parameter 'check_joint' = 'nosuch': " + (dir / "rec").string() +
                          " recorded no such joint column (its joint columns: sensing_finger); name one with --set "
                          "devices.tactile.params.check_joint=JOINT") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "rep" / "manifest.csv"));
}
