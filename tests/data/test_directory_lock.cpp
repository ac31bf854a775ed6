// One writer per output folder: a second DatasetWriter, or a second
// `rollsense run` into the same --out, is refused at once with a message that
// says what to do; the lock goes with the writer (or the process).
#include <catch2/catch.hpp>

#include "rollsense/dataset.hpp"
#include "rollsense/directory_lock.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"
#include "tiny_dataset.hpp"

using namespace rollsense;
using rollsense::testing::TempDir;
using rollsense::testing::tiny_info;

TEST_CASE("a second writer into the same folder is refused while the first lives", "[data][lock]") {
    TempDir dir;
    auto first = DatasetWriter::open(dir / "ds", tiny_info(), DatasetOpenMode::create);
    REQUIRE(first.ok());
    auto second = DatasetWriter::open(dir / "ds", tiny_info(), DatasetOpenMode::resume);
    REQUIRE_FALSE(second.ok());
    CHECK(second.error().code == ErrorCode::state_error);
    CHECK_THAT(second.error().message, Catch::Contains("being written by another rollsense run") &&
                                           Catch::Contains("--out"));
    first->reset();
    auto third = DatasetWriter::open(dir / "ds", tiny_info(), DatasetOpenMode::resume);
    CHECK(third.ok());
}

TEST_CASE("`rollsense run` into a folder another run holds exits at once, naming it", "[data][lock][cli]") {
    TempDir dir;
    std::filesystem::create_directories(dir / "out");
    auto held = DirectoryLock::acquire(dir / "out");
    REQUIRE(held.ok());
    auto r = rollsense::testing::run_rollsense("run " + std::string(ROLLSENSE_SOURCE_DIR) +
                                               "/scripts/paper_experiment.lua --set runs=1 --no-progress --out " +
                                               (dir / "out").string());
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains((dir / "out").string() + " is being written by another rollsense run"));
    CHECK_FALSE(std::filesystem::exists(dir / "out" / "manifest.csv"));
}

// Review: a resume into a folder another run is recording failed as a run of its own: exit 1, "failed: 0 trials
// saved, N already on disk", advice about editing the script and a "continue with: ... --resume" line.
TEST_CASE("`rollsense run --resume` into a folder another run is recording is refused once, exit 2", "[data][lock][cli]") {
    TempDir dir;
    const std::string run = "run " + std::string(ROLLSENSE_SOURCE_DIR) +
                            "/scripts/paper_experiment.lua --set runs=1 --set analyse=false --no-progress -q --out " +
                            (dir / "out").string();
    REQUIRE(rollsense::testing::run_rollsense(run).status == 0);
    auto held = DirectoryLock::acquire(dir / "out");
    REQUIRE(held.ok());
    auto r = rollsense::testing::run_rollsense(run + " --resume");
    INFO(r.output);
    CHECK(r.status == 2);
    const std::string refusal = (dir / "out").string() + " is being written by another rollsense run";
    CHECK(r.output.find(refusal) != std::string::npos);
    CHECK(r.output.find(refusal) == r.output.rfind(refusal));  // once
    CHECK_THAT(r.output, !Catch::Contains("failed:") && !Catch::Contains("continue with") &&
                             !Catch::Contains("already on disk"));
}

TEST_CASE("out-of-range numbers on the command line are usage errors, not silent changes", "[data][cli]") {
    const std::string script = "run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/paper_experiment.lua --out /nonexistent ";
    for (const char* bad : {"--memory-limit-mb -1", "--memory-limit-mb 0", "--slice-limit-ms 0", "--seed 1e30",
                            "--seed -1", "--seed 2.5", "--time-limit -1", "--commit-every x"}) {
        auto r = rollsense::testing::run_rollsense(script + bad);
        INFO(bad << "\n" << r.output);
        CHECK(r.status == 2);
        CHECK_THAT(r.output, Catch::Contains(std::string(bad).substr(0, std::string(bad).find(' '))));
    }
}
