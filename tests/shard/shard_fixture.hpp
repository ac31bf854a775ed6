// Shared by the shard tests: recording the stock experiment (whole or one
// shard) through the `rollsense` program, and comparing datasets file by file.
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <initializer_list>
#include <string>

#include "run_command.hpp"
#include "temp_dir.hpp"

namespace rollsense::testing {

inline std::string paper_experiment() { return std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/paper_experiment.lua"; }

// `rollsense run scripts/paper_experiment.lua --seed 11 OPTIONS --out OUT`, quiet.
inline CommandRun record(const std::filesystem::path& out, const std::string& options) {
    return run_rollsense("run " + paper_experiment() + " --seed 11 -q --no-progress " + options + " --out " +
                         out.string());
}

// Every trial file of `a` has a byte-identical twin in `b` and vice versa;
// returns how many there are.
inline std::size_t same_trials(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(a / "trials")) {
        INFO(e.path());
        CHECK(read_file(e.path()) == read_file(b / "trials" / e.path().filename()));
        ++n;
    }
    CHECK(static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(b / "trials"),
                                                 std::filesystem::directory_iterator())) == n);
    return n;
}

inline void same_files(const std::filesystem::path& a, const std::filesystem::path& b,
                       std::initializer_list<const char*> names) {
    for (const char* name : names) {
        INFO(name);
        REQUIRE(std::filesystem::exists(a / name));
        CHECK(read_file(a / name) == read_file(b / name));
    }
}

inline std::size_t manifest_trials(const std::filesystem::path& dataset) {
    const auto text = read_file(dataset / "manifest.csv");
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) - 1;
}

}  // namespace rollsense::testing
