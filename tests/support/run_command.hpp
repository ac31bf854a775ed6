// Running a program from a test: its exit status and everything it printed
// (stdout and stderr together).
#pragma once

#include <catch2/catch.hpp>

#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace rollsense::testing {

struct CommandRun {
    int status = -1;  // exit code; -1 if it did not exit normally
    std::string output;
};

inline CommandRun run_command(const std::string& command) {
    CommandRun r;
    std::FILE* p = ::popen((command + " 2>&1").c_str(), "r");
    REQUIRE(p != nullptr);
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p)) r.output += buf;
    const int st = ::pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

// Counts non-overlapping occurrences of `needle` (a message printed once, not twice).
inline std::size_t count_of(const std::string& hay, const std::string& needle) {
    std::size_t n = 0;
    for (auto pos = hay.find(needle); pos != std::string::npos; pos = hay.find(needle, pos + needle.size())) ++n;
    return n;
}

// `rollsense ARGS` from this build.
inline CommandRun run_rollsense(const std::string& args) {
    return run_command(std::string(ROLLSENSE_BIN_DIR) + "/rollsense " + args);
}

}  // namespace rollsense::testing
