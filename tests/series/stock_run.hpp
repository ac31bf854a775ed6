// One small stock run made through the program (the simulated hand, one run
// per object and speed: 27 trials), made once per test process.
#pragma once

#include <filesystem>
#include <string>

#include "rollsense/dataset.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"

namespace rollsense::testing {

inline const std::filesystem::path& stock_run_dir() {
    static TempDir dir("rollsense-series");
    static const std::filesystem::path made = [] {
        const auto out = dir.path() / "run";
        const auto run = run_rollsense("run " + std::string(ROLLSENSE_SOURCE_DIR) +
                                       "/scripts/paper_experiment.lua --profile sim --set runs=1 "
                                       "--set analyse=false --seed 11 -q --out " + out.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        return out;
    }();
    return made;
}

inline const DatasetReader& stock_run() {
    static const DatasetReader reader = [] {
        auto r = DatasetReader::open(stock_run_dir());
        REQUIRE(r.ok());
        return *r;
    }();
    return reader;
}

}  // namespace rollsense::testing
