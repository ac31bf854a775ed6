// scripts/examples/identify_early.lua end to end, small: prefix models trained
// on the small stock run, a few held-out rolls of another seed; the rule must
// stop some rolls before their end and the script must report its figures.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "run_command.hpp"
#include "stock_run.hpp"
#include "temp_dir.hpp"

TEST_CASE("identify_early.lua stops rolls early and reports time and accuracy", "[series][lua][early]") {
    rollsense::testing::TempDir dir("rollsense-early");
    const auto out = dir.path() / "run";
    const auto run = rollsense::testing::run_rollsense(
        "run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/examples/identify_early.lua --profile sim --seed 23 " +
        "--set train=" + rollsense::testing::stock_run_dir().string() +
        " --set runs=1 --set objects=P1,H2,C1 --set speeds=10,20 --set threshold=0.3 --set k=2 --set from=0.5 --out " +
        out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("early identification: threshold 0.30, k 2, from 50 %"));
    CHECK_THAT(run.output, Catch::Contains("all          6 rolls"));
    CHECK(std::filesystem::exists(out / "prefix-f100.rsm"));

    // identify-early.csv: one row per object and speed; some rolls stopped
    // early, and those recorded less than their full roll.
    std::ifstream csv(out / "identify-early.csv");
    REQUIRE(csv);
    std::string line;
    std::getline(csv, line);
    CHECK(line == "object,speed,repetition,early_answer,early_stopped,early_seconds,early_fraction,full_answer,"
                  "full_seconds");
    int rows = 0, stopped = 0;
    while (std::getline(csv, line)) {
        ++rows;
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
        REQUIRE(f.size() == 9);
        if (f[4] == "true") {
            ++stopped;
            CHECK(std::stod(f[5]) < std::stod(f[8]));  // the early roll was shorter than the full one
            CHECK(std::stod(f[6]) >= 0.5);             // not before `from` (0.5) on the contact's clock
            CHECK_FALSE(f[3].empty());                 // and gave an answer
        }
    }
    CHECK(rows == 6);
    CHECK(stopped >= 1);
}

// User review: a speed the training recording lacks was found only after every prefix model was trained (seconds).
TEST_CASE("identify_early.lua refuses a speed its training recording lacks before training any model",
          "[series][lua][early][errors]") {
    rollsense::testing::TempDir dir("rollsense-early-speed");
    const auto out = dir.path() / "run";
    const std::string train = rollsense::testing::stock_run_dir().string();
    const auto run = rollsense::testing::run_rollsense(
        "run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/examples/identify_early.lua --profile sim --seed 23 " +
        "--set train=" + train + " --set speeds=10,25 --out " + out.string());
    INFO(run.output);
    CHECK(run.status != 0);
    CHECK_THAT(run.output, Catch::Contains("rs.prefix_models: speed 25 is not among the trials of " + train +
                                           " (its speeds: 10, 15, 20)") &&
                               Catch::Contains("record that speed, or leave it out"));
    CHECK_FALSE(std::filesystem::exists(out / "prefix-f010.rsm"));
    CHECK_FALSE(std::filesystem::exists(out / "prefix-f100.rsm"));
}
