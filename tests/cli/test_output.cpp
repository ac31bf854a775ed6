// What the program prints: `help CMD`, each error once, colour only where
// wanted, --log-time.
#include <catch2/catch.hpp>

#include <regex>

#include "cli_helpers.hpp"

using namespace rollsense::testing;
namespace fs = std::filesystem;

TEST_CASE("`rollsense help CMD` prints what `rollsense CMD --help` prints") {
    for (const char* cmd : {"run", "features", "train", "predict", "evaluate", "report", "merge", "view", "dxl",
                             "plugins", "probe"}) {
        INFO(cmd);
        const auto a = run_rollsense(std::string("help ") + cmd);
        const auto b = run_rollsense(std::string(cmd) + " --help");
        CHECK(a.status == 0);
        CHECK(b.status == 0);
        CHECK(a.output == b.output);
        CHECK(a.output.find(std::string("usage: rollsense ") + cmd) != std::string::npos);
    }
    const auto unknown = run_rollsense("help nosuch");
    CHECK(unknown.status == 2);
    CHECK(unknown.output.find("unknown command 'nosuch'") != std::string::npos);
    CHECK(run_rollsense("help").status == 0);
}

TEST_CASE("a failed script's error is printed once") {
    TempDir dir("rollsense-cli-once");
    write_file(dir / "fail.lua", "error('unmistakable failure text')\n");
    const auto r = run_rollsense("run " + shell_quoted(dir / "fail.lua") + " --profile mock --out " + shell_quoted(dir / "out"));
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(count_of(r.output, "unmistakable failure text") == 1);
    // ...with where it happened
    CHECK(r.output.find("fail.lua:1:") != std::string::npos);
}

// Independent review, run item 3: the "failed: 0 trials saved" summary came
// before the error it summed up. The error first, once, then the summary.
TEST_CASE("a failed run prints its error before the summary line, once") {
    TempDir dir("rollsense-cli-once");
    write_file(dir / "late.lua", "local rs = require 'rollsense'\nrs.trial{ object = 'C1', speed = 10, repetition = 1 }\n"
                                 "rs.record_start()\nrs.wait(200)\nrs.record_stop()\nrs.save_trial()\nrs.end_trial()\n"
                                 "error('unmistakable late failure')\n");
    write_file(dir / "early.lua", "error('unmistakable early failure')\n");
    for (const char* name : {"late", "early"}) {
        INFO(name);
        const auto r = run_rollsense("run " + shell_quoted(dir / (std::string(name) + ".lua")) + " --profile mock --out " +
                                     shell_quoted(dir / name));
        INFO(r.output);
        CHECK(r.status == 1);
        const std::string error = std::string("unmistakable ") + name + " failure";
        CHECK(count_of(r.output, error) == 1);
        REQUIRE(r.output.find("failed: ") != std::string::npos);
        CHECK(r.output.find(error) < r.output.find("failed: "));
    }
    // A dataset refused when the run opens it (a manifest without its trials): the error, then the summary.
    fs::create_directories(dir / "foreign");
    fs::copy_file(dir / "late" / "manifest.csv", dir / "foreign" / "manifest.csv");
    const auto refused = run_rollsense("run " + shell_quoted(dir / "late.lua") + " --profile mock --resume --out " +
                                       shell_quoted(dir / "foreign"));
    INFO(refused.output);
    CHECK(refused.status == 3);
    CHECK(count_of(refused.output, "cannot resume") == 1);
    REQUIRE(refused.output.find("failed: ") != std::string::npos);
    const auto at = refused.output.find("cannot resume");
    CHECK(at != std::string::npos);
    CHECK(at < refused.output.find("failed: "));
}

TEST_CASE("a failure inside a C++ call from the script is printed once") {
    TempDir dir("rollsense-cli-once");
    write_file(dir / "bad_joint.lua", "local rs = require 'rollsense'\nrs.joint('no_such_joint_here')\n");
    const auto r = run_rollsense("run " + shell_quoted(dir / "bad_joint.lua") + " --profile mock --out " + shell_quoted(dir / "out"));
    INFO(r.output);
    CHECK(r.status != 0);
    CHECK(count_of(r.output, "no_such_joint_here") == 1);
}

TEST_CASE("log lines are coloured on a terminal, and not with NO_COLOR or off a terminal") {
    TempDir dir("rollsense-cli-colour");
    write_file(dir / "warn.lua", "local rs = require 'rollsense'\nrs.warn('a warning line')\nerror('and an error')\n");
    int n = 0;  // a fresh output folder for every run
    auto args_for = [&] {
        return std::vector<std::string>{"run",   (dir / "warn.lua").string(), "--profile", "mock", "--no-progress",
                                        "--out", (dir / ("out" + std::to_string(n++))).string()};
    };
    auto args = args_for();
    const auto coloured = run_on_terminal(args, {"NO_COLOR=", "TERM=xterm"});
    INFO(coloured.output);
    CHECK(coloured.output.find("a warning line") != std::string::npos);
    CHECK(coloured.output.find("\033[") != std::string::npos);

    args = args_for();
    const auto plain = run_on_terminal(args, {"NO_COLOR=1", "TERM=xterm"});
    INFO(plain.output);
    CHECK(plain.output.find("a warning line") != std::string::npos);
    CHECK(plain.output.find('\033') == std::string::npos);

    args = args_for();
    const auto dumb = run_on_terminal(args, {"NO_COLOR=", "TERM=dumb"});
    CHECK(dumb.output.find('\033') == std::string::npos);

    args = args_for();
    std::string piped_cmd = "env -u NO_COLOR " + rollsense_bin();
    for (std::size_t i = 0; i < args.size(); ++i) piped_cmd += " " + shell_quoted(args[i]);
    const auto piped = run_command(piped_cmd);
    CHECK(piped.output.find("a warning line") != std::string::npos);
    CHECK(piped.output.find('\033') == std::string::npos);
}

TEST_CASE("the global option log-time starts every log line with the UTC time, before or after the command") {
    TempDir dir("rollsense-cli-time");
    write_file(dir / "warn.lua", "local rs = require 'rollsense'\nrs.warn('timed warning')\n");
    const std::string script = shell_quoted(dir / "warn.lua");
    const std::regex stamped(R"((^|\n)\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z warning +\S+: timed warning)");
    for (const std::string& args :
         {"--log-time run " + script + " --profile mock --out " + shell_quoted(dir / "a"),
          "run " + script + " --profile mock --out " + shell_quoted(dir / "b") + " --log-time"}) {
        const auto r = run_rollsense(args);
        INFO(r.output);
        CHECK(r.status == 0);
        CHECK(std::regex_search(r.output, stamped));
    }
    const auto plain = run_rollsense("run " + script + " --profile mock --out " + shell_quoted(dir / "c"));
    CHECK_FALSE(std::regex_search(plain.output, std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d)")));
}

// The progress bar is drawn with carriage returns and no newline: a log line
// printed while it was drawn used to continue the bar's line.
TEST_CASE("on a terminal a log line during the progress bar starts a line of its own and --no-progress draws none") {
    TempDir dir("rollsense-cli-progress");
    write_file(dir / "steps.lua", "local rs = require 'rollsense'\nfor i = 1, 3 do\n  rs.wait(1)\n"
                                  "  rs.progress(i, 3, 'steps')\n  if i == 1 then rs.log('after the first step') end\nend\n");
    const std::vector<std::string> args{"run", (dir / "steps.lua").string(), "--profile", "mock", "--out",
                                        (dir / "out").string()};
    const auto drawn = run_on_terminal(args, {"NO_COLOR=1", "TERM=xterm"});
    INFO(drawn.output);
    REQUIRE(drawn.status == 0);
    CHECK(drawn.output.find("] 1/3 steps") != std::string::npos);
    CHECK(drawn.output.find("] 3/3 steps") != std::string::npos);
    const auto logged = drawn.output.find("info    script: after the first step");
    REQUIRE(logged != std::string::npos);
    REQUIRE(logged > 0);
    CHECK(drawn.output[logged - 1] == '\n');
    // The summary after the bar starts a line of its own too.
    const auto done = drawn.output.find("done: 0 trials saved");
    REQUIRE(done != std::string::npos);
    CHECK(drawn.output[done - 1] == '\n');

    auto quiet_args = args;
    quiet_args.back() = (dir / "quiet").string();
    quiet_args.push_back("--no-progress");
    const auto quiet = run_on_terminal(quiet_args, {"NO_COLOR=1", "TERM=xterm"});
    INFO(quiet.output);
    CHECK(quiet.status == 0);
    CHECK(quiet.output.find("steps") == std::string::npos);
    CHECK(quiet.output.find("after the first step") != std::string::npos);
}
