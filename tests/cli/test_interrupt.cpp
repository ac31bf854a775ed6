// Ctrl-C during the analysis (issue 24 item 5): SIGINT sent to a child
// `rollsense` once its analysis has begun stops it with the interrupted exit
// code (130) and message, instead of being ignored (rs.analyse: until the
// watchdog's last resort) or killing the program (evaluate: no handler).
#include <catch2/catch.hpp>

#include <csignal>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_helpers.hpp"

namespace {
using namespace rollsense::testing;
namespace fs = std::filesystem;

// Starts `rollsense args...` with stdout and stderr on a pipe, sends SIGINT
// once its output contains `marker`, and returns everything it printed and
// its exit status (-1: killed by a signal).
CommandRun interrupt_when(const std::vector<std::string>& args, const std::string& marker) {
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ::dup2(fds[1], 1);
        ::dup2(fds[1], 2);
        ::close(fds[0]);
        ::close(fds[1]);
        exec_rollsense(args);
    }
    ::close(fds[1]);
    CommandRun r;
    bool sent = false;
    char buf[4096];
    for (;;) {
        const ssize_t n = ::read(fds[0], buf, sizeof buf);
        if (n <= 0) break;
        r.output.append(buf, static_cast<std::size_t>(n));
        if (!sent && r.output.find(marker) != std::string::npos) {
            ::kill(pid, SIGINT);
            sent = true;
        }
    }
    ::close(fds[0]);
    int st = 0;
    ::waitpid(pid, &st, 0);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    INFO(r.output);
    REQUIRE(sent);  // the marker was seen: the signal came during the analysis
    return r;
}

const fs::path kPaper = fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "paper_experiment.lua";

}  // namespace

TEST_CASE("Ctrl-C during rs.analyse's optimisation ends the run as interrupted") {
    TempDir dir("rollsense-cli-interrupt-analyse");
    const auto r = interrupt_when({"run", kPaper.string(), "--set", "runs=4", "--set", "optimize=true", "--seed", "3",
                                   "--no-progress", "--out", (dir / "run").string()},
                                  "optimiser 1:");
    INFO(r.output);
    CHECK(r.status == 130);
    CHECK(r.output.find("interrupted by Ctrl-C or a SIGTERM/SIGHUP") != std::string::npos);
    CHECK(r.output.find("did not stop within") == std::string::npos);  // not the watchdog's last resort
    CHECK(fs::exists(dir / "run" / "run-info.csv"));  // the run ended the ordinary way
    // Stopped, not failed: a resume runs the analysis again and can finish it.
    CHECK(r.output.find("continue with: rollsense run ") != std::string::npos);
    CHECK(r.output.find("the analysis failed") == std::string::npos);
}

TEST_CASE("Ctrl-C during rollsense evaluate ends it as interrupted") {
    TempDir dir("rollsense-cli-interrupt-evaluate");
    const auto rec = run_rollsense("run " + shell_quoted(kPaper) + " --set runs=4 --set analyse=false --no-progress -q --out " +
                                   shell_quoted(dir / "run"));
    INFO(rec.output);
    REQUIRE(rec.status == 0);
    const auto r = interrupt_when({"evaluate", (dir / "run").string(), "--optimize", "--evaluations", "200"}, "optimiser 1:");
    INFO(r.output);
    CHECK(r.status == 130);
    CHECK(r.output.find("interrupted by Ctrl-C or a SIGTERM/SIGHUP") != std::string::npos);
}

// Review (scripting): a task that spawns a task and ends kept the scheduler's pass going forever, past Ctrl-C, the
// time limit and the control period; only the third Ctrl-C (the watchdog's last resort) ended it, without cleanup.
TEST_CASE("Ctrl-C stops a chain of spawned tasks, and the cleanup runs") {
    TempDir dir("rollsense-cli-interrupt-chain");
    {
        std::ofstream(dir / "chain.lua") << "local rs = require 'rollsense'\n"
                                            "rs.on_cleanup(function() rs.log('cleanup ran') end)\n"
                                            "rs.log('chain starts')\n"
                                            "local function chain() rs.spawn(chain) end\n"
                                            "chain()\n"
                                            "rs.wait(1000)\n";
    }
    const auto r = interrupt_when({"run", (dir / "chain.lua").string(), "--no-progress", "--out", (dir / "out").string()},
                                  "chain starts");
    INFO(r.output);
    CHECK(r.status == 130);
    CHECK(r.output.find("cleanup ran") != std::string::npos);
    CHECK(r.output.find("interrupted three times") == std::string::npos);
}

// The watchdog's way out ends the process inside the run, where `rollsense run` could not say how to go on (review:
// no "continue with" line, though the trials recorded before stayed on disk).
TEST_CASE("the watchdog's way out names the resume command when trials were saved") {
    TempDir dir("rollsense-cli-watchdog-way-on");
    {
        std::ofstream(dir / "stuck.lua") << "local rs = require 'rollsense'\n"
                                            "local id = rs.trial_id{ object = 'C1', speed = 20, repetition = 1 }\n"
                                            "if not rs.has_trial(id) then\n"
                                            "  rs.trial{ object = 'C1', speed = 20, repetition = 1 }\n"
                                            "  rs.record_start() rs.wait(100) rs.record_stop() rs.save_trial()\n"
                                            "  rs.end_trial()\n"
                                            "end\n"
                                            "table.move({}, 1, 1 << 62, 1, {})  -- one C call no hook reaches\n";
    }
    const std::string command = "run " + shell_quoted(dir / "stuck.lua") + " --slice-limit-ms 200 --no-progress --out " +
                                shell_quoted(dir / "out");
    const std::string way_on = "continue with: rollsense run " + (dir / "stuck.lua").string() + " --out " +
                               (dir / "out").string() + " --resume";  // plain paths: unquoted
    const auto r = run_rollsense(command);
    INFO(r.output);
    CHECK(r.status == 1);  // the script's failure, a limit it passed
    CHECK(r.output.find("the watchdog made the hand safe") != std::string::npos);
    CHECK(r.output.find("after a script stuck in one call, fix it and record into a new --out") != std::string::npos);
    CHECK(r.output.find(way_on) != std::string::npos);
    CHECK(fs::exists(dir / "out" / "trials" / "C1-v20-r001.csv"));
    // Resumed, it saves nothing new before it sticks again: the trial on disk still makes the way on worth saying.
    const auto again = run_rollsense(command + " --resume");
    INFO(again.output);
    CHECK(again.status == 1);
    CHECK(again.output.find(way_on) != std::string::npos);
}

// Diff review: stuck in its cleanup, after the script's end, the watchdog's way out still offered a resume, which
// would record nothing (the script's own end already says so, since this stop).
TEST_CASE("the watchdog's way out offers no resume when the script had ended and its cleanup stuck") {
    TempDir dir("rollsense-cli-watchdog-cleanup");
    {
        std::ofstream(dir / "stuck.lua") << "local rs = require 'rollsense'\n"
                                            "rs.on_cleanup(function() table.move({}, 1, 1 << 62, 1, {}) end)\n"
                                            "rs.trial{ object = 'C1', speed = 20, repetition = 1 }\n"
                                            "rs.record_start() rs.wait(100) rs.record_stop() rs.save_trial()\n"
                                            "rs.end_trial()\n";
    }
    const auto r = run_rollsense("run " + shell_quoted(dir / "stuck.lua") + " --slice-limit-ms 200 --no-progress --out " +
                                 shell_quoted(dir / "out"));
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(r.output.find("the watchdog made the hand safe") != std::string::npos);
    CHECK(r.output.find("continue with:") == std::string::npos);
    // What it says instead (second diff review: it said nothing about the trial on disk).
    CHECK(r.output.find("the script ran to its end and its trials are on disk; what failed came after it (above): a "
                        "resume would record nothing") != std::string::npos);
    CHECK(fs::exists(dir / "out" / "trials" / "C1-v20-r001.csv"));
}
