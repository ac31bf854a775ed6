// Exit codes: one table, the same in README.md and `rollsense --help`, and the
// codes the program really returns for each kind of failure.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>

#include "cli_helpers.hpp"

namespace {
using namespace rollsense::testing;
namespace fs = std::filesystem;

// (code, meaning) rows of the README's "### Exit codes" table.
std::vector<std::pair<std::string, std::string>> readme_table() {
    std::istringstream in(read_file(fs::path(ROLLSENSE_SOURCE_DIR) / "README.md"));
    std::vector<std::pair<std::string, std::string>> rows;
    bool inside = false;
    const std::regex row(R"(^\| (\d+) \| (.+) \|$)");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("### Exit codes", 0) == 0) inside = true;
        else if (inside && line.rfind("#", 0) == 0) break;
        std::smatch m;
        if (inside && std::regex_match(line, m, row)) rows.emplace_back(m[1], m[2]);
    }
    return rows;
}

// (code, meaning) lines after "exit codes:" in `rollsense --help`.
std::vector<std::pair<std::string, std::string>> help_table(const std::string& help) {
    std::vector<std::pair<std::string, std::string>> rows;
    const auto at = help.find("\nexit codes:\n");
    REQUIRE(at != std::string::npos);
    std::istringstream in(help.substr(at + 13));
    const std::regex row(R"(^  (\d+) +(.+)$)");
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (!std::regex_match(line, m, row)) break;
        rows.emplace_back(m[1], m[2]);
    }
    return rows;
}

}  // namespace

TEST_CASE("the README's exit-code table is the one `rollsense --help` prints") {
    const auto help = run_rollsense("--help");
    REQUIRE(help.status == 0);
    const auto printed = help_table(help.output);
    const auto documented = readme_table();
    REQUIRE(printed.size() >= 7);
    CHECK(documented == printed);
    // I/O errors have a code of their own, not "hardware".
    bool io = false;
    for (const auto& [code, meaning] : printed) io = io || (code == "5" && meaning.find("disk full") != std::string::npos);
    CHECK(io);
}

TEST_CASE("a disk that refuses writes exits 5, not 4 (hardware)") {
    TempDir dir("rollsense-cli-io");
    // A file-size limit of 0 makes every write fail (EFBIG) the way a full
    // disk does (ENOSPC); SIGXFSZ is ignored so the write returns the error.
    const auto r = run_command("trap '' XFSZ; ulimit -f 0; " + rollsense_bin() + " run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/demo_roll.lua --profile mock --out " +
                               shell_quoted(dir / "out") + " --no-progress");
    INFO(r.output);
    CHECK(r.status == 5);
    CHECK(r.output.find("I/O error") != std::string::npos);
}

// Review: `--out FILE` was "I/O error: FILE: cannot create: Not a directory",
// exit 5. A file where the folder should be is a bad command line, refused before
// the run like a folder holding other files, and so is a path through a file.
TEST_CASE("an --out that is a file, or under a regular file, is a bad command line (2), named") {
    TempDir dir("rollsense-cli-io");
    write_file(dir / "file", "x");
    const std::string run = "run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/demo_roll.lua --profile mock --no-progress --out ";
    auto r = run_rollsense(run + shell_quoted(dir / "file"));
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK(r.output.find("--out " + (dir / "file").string() + ": is a file, not a folder (choose a new or empty folder") !=
          std::string::npos);
    CHECK(r.output.find("I/O error") == std::string::npos);
    r = run_rollsense(run + shell_quoted(dir / "file" / "out"));
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK(r.output.find("--out " + (dir / "file" / "out").string() + ": " + (dir / "file").string() +
                        " is a file, not a folder") != std::string::npos);
    CHECK(read_file(dir / "file") == "x");
}

TEST_CASE("other failures keep their codes") {
    TempDir dir("rollsense-cli-codes");
    CHECK(run_rollsense("").status == 2);
    CHECK(run_rollsense("nosuch").status == 2);
    CHECK(run_rollsense("run").status == 2);
    CHECK(run_rollsense("run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/demo_roll.lua --bogus").status == 2);
    CHECK(run_rollsense("run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/demo_roll.lua --profile nosuch --out " + shell_quoted(dir / "a")).status == 3);
    // A profile that parses but says something wrong is a bad input file too (review finding 19: it exited 1).
    write_file(dir / "bad-limits.lua", "return { clock = 'virtual', sample_rate_hz = 31.1, control_rate_hz = 100,\n"
                                       "  devices = { hand = include('mock-hand') }, joints = { winchh = { min = 0, max = 1 } } }\n");
    const auto bad_profile = run_rollsense("run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/demo_roll.lua --profile " +
                                           shell_quoted(dir / "bad-limits.lua") + " --out " + shell_quoted(dir / "d"));
    INFO(bad_profile.output);
    CHECK(bad_profile.status == 3);
    CHECK(bad_profile.output.find("has no limits") != std::string::npos);
    write_file(dir / "fail.lua", "error('the script gives up')\n");
    CHECK(run_rollsense("run " + shell_quoted(dir / "fail.lua") + " --profile mock --out " + shell_quoted(dir / "b")).status == 1);
    write_file(dir / "slow.lua", "local rs = require 'rollsense'\nrs.wait(60000)\n");
    CHECK(run_rollsense("run " + shell_quoted(dir / "slow.lua") + " --profile mock --time-limit 1 --out " + shell_quoted(dir / "c"))
              .status == 130);
}

// Diff review: a controller the profile lacks exited 3 ("bad profile"), a joint or a device the profile lacks 1; all
// three are the script's mistake, as the table says. A script that does not parse is a bad input file (3), a joint that
// did not arrive within its move's timeout a device's failure (4): the table says so too.
TEST_CASE("a name the profile lacks is the script's mistake (1), a script that does not parse 3, a missed move 4") {
    TempDir dir("rollsense-cli-codes-script");
    const auto run = [&](const std::string& name, const std::string& body) {
        write_file(dir / (name + ".lua"), "local rs = require 'rollsense'\n" + body + "\n");
        return run_rollsense("run " + shell_quoted(dir / (name + ".lua")) + " --out " + shell_quoted(dir / name));
    };
    const auto controller = run("controller", "rs.controller('nope', true)");
    INFO(controller.output);
    CHECK(controller.status == 1);
    CHECK(count_of(controller.output, "controller.lua:2: no controller 'nope' in profile 'sim'") == 1);
    // Switched off too (diff review: it passed in silence, leaving a misspelt controller on).
    const auto off = run("off", "rs.controller('nope', false)");
    CHECK(off.status == 1);
    CHECK(count_of(off.output, "off.lua:2: no controller 'nope' in profile 'sim'") == 1);
    // A controller the profile configures with a joint it lacks is the profile's mistake (3), not the script's.
    write_file(dir / "bad-controller.lua", "local p = include('sim')\n"
                                           "p.controllers = { palm_parallel = { sensing = 'nope_joint' } }\nreturn p\n");
    write_file(dir / "profiled.lua", "local rs = require 'rollsense'\nrs.controller('palm_parallel', true)\n");
    const auto profiled = run_rollsense("run " + shell_quoted(dir / "profiled.lua") + " --profile " +
                                        shell_quoted(dir / "bad-controller.lua") + " --out " + shell_quoted(dir / "p"));
    INFO(profiled.output);
    CHECK(profiled.status == 3);
    CHECK(count_of(profiled.output, "no joint 'nope_joint' (set controllers.palm_parallel.sensing in the profile)") == 1);
    // The same refusal in a rs.wait_until condition keeps its code (diff review: exit 1).
    write_file(dir / "waiting.lua", "local rs = require 'rollsense'\n"
                                    "rs.wait_until(function() rs.controller('palm_parallel', true) return true end)\n");
    const auto waiting = run_rollsense("run " + shell_quoted(dir / "waiting.lua") + " --profile " +
                                       shell_quoted(dir / "bad-controller.lua") + " --out " + shell_quoted(dir / "w"));
    INFO(waiting.output);
    CHECK(waiting.status == 3);
    CHECK(count_of(waiting.output, "wait_until condition failed: ") == 1);
    CHECK(run("joint", "rs.joint('nope')").status == 1);
    // A refusal a pcall caught does not lend its code to a later error of the script's own (diff review: exit 3 for an
    // error('...')); raised again before another refusal, it keeps it.
    const std::string refused = "local ok, e = pcall(rs.trial, { object = 'Z9', speed = 10, repetition = 1 })\n";
    const auto own = run("own", refused + "error('the script gives up')");
    INFO(own.output);
    CHECK(own.status == 1);
    CHECK(run("again", refused + "error(e, 0)").status == 3);
    CHECK(run("device", "rs.device('nope')").status == 1);
    const auto syntax = run("syntax", "local x = = 1");
    INFO(syntax.output);
    CHECK(syntax.status == 3);
    CHECK(count_of(syntax.output, "syntax.lua:2: unexpected symbol near '='") == 1);
    // A module that does not parse is as much the script's file (user review: exit 1 through require, 3 in the script).
    fs::create_directories(dir / "lib");
    write_file(dir / "lib" / "broken.lua", "local M = {}\nfunction M.f(\nreturn M\n");
    const auto module = run("module", "local broken = require 'lib.broken'");
    INFO(module.output);
    CHECK(module.status == 3);
    CHECK(count_of(module.output, "require('lib.broken'): ") == 1);
    CHECK(count_of(module.output, "broken.lua:3: <name> or '...' expected near 'return'") == 1);
    const auto missed = run("missed", "rs.joint('palm'):move(100, {timeout_ms = 1})");
    INFO(missed.output);
    CHECK(missed.status == 4);
    CHECK(count_of(missed.output, "missed.lua:2: timed out waiting for joint 'palm'") == 1);
}

// Review finding 18: "'2' is not a number in 5-252" for a reversed range, "frob needs --id N"
// for an unknown action, and any --baud accepted while --new-baud knew the X-series rates.
TEST_CASE("dxl's bad arguments are usage errors (2) that say what is wrong") {
    const auto reversed = run_rollsense("dxl scan --device /nonexistent-bus --ids 5-2");
    INFO(reversed.output);
    CHECK(reversed.status == 2);
    CHECK(reversed.output.find("--ids 5-2: the range is reversed (FIRST-LAST, e.g. 2-5)") != std::string::npos);
    const auto action = run_rollsense("dxl frob --device /nonexistent-bus");
    INFO(action.output);
    CHECK(action.status == 2);
    CHECK(action.output.find("unknown action 'frob' (scan, info, reboot, set-id, set-baud)") != std::string::npos);
    const std::string rates = " is not an X-series rate (9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000, 4500000)";
    const auto baud = run_rollsense("dxl scan --device /nonexistent-bus --baud 12345");
    INFO(baud.output);
    CHECK(baud.status == 2);
    CHECK(baud.output.find("--baud: 12345" + rates) != std::string::npos);
    const auto new_baud = run_rollsense("dxl set-baud --device /nonexistent-bus --id 1 --new-baud 12345");
    CHECK(new_baud.status == 2);
    CHECK(new_baud.output.find("--new-baud: 12345" + rates) != std::string::npos);
}

// Independent review, run item 5: the slice limit exited 130, as a Ctrl-C does;
// a script that runs away is the script's failure (1), named at its line, and
// so is a profile that does (3, a bad profile).
TEST_CASE("a script that runs past --slice-limit-ms fails (1) at its file:line, naming the limit") {
    TempDir dir("rollsense-cli-codes");
    write_file(dir / "loop.lua", "local x = 0\nwhile true do\n  x = x + 1\nend\n");
    const auto r = run_rollsense("run " + shell_quoted(dir / "loop.lua") + " --profile mock --slice-limit-ms 200 --out " +
                                 shell_quoted(dir / "a"));
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(r.output.find("loop.lua:3: the script ran ") != std::string::npos);
    CHECK(r.output.find("past --slice-limit-ms 200") != std::string::npos);
    CHECK(count_of(r.output, "without waiting") == 1);
    CHECK(r.output.find("failed: 0 trials saved") != std::string::npos);
    CHECK(r.output.find("cancelled") == std::string::npos);

    write_file(dir / "loop-profile.lua", "local p = include('mock')\nlocal i = 0\nwhile true do i = i + 1 end\nreturn p\n");
    const auto p = run_rollsense("run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/demo_roll.lua --profile " +
                                 shell_quoted(dir / "loop-profile.lua") + " --slice-limit-ms 200 --out " + shell_quoted(dir / "b"));
    INFO(p.output);
    CHECK(p.status == 3);
    CHECK(p.output.find("loop-profile.lua:3: the profile ran ") != std::string::npos);
    CHECK(p.output.find("past --slice-limit-ms 200") != std::string::npos);
}
