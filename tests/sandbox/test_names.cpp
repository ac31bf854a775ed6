// Items 9 and 10 of issue 22: output names that would overwrite the dataset or
// leave the output folder are refused before anything is written; modules
// are plain dotted names found only under the allowed roots.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include "limited_child.hpp"

using namespace rollsense;

TEST_CASE("rs.write_output refuses the dataset's own files and unsafe names", "[sandbox][names]") {
    const std::string names[] = {"manifest.csv", "dataset-info.csv", "run-info.csv", "features.csv", "trials",
                                 "run-config.csv", "shard-plan.csv", "shards.csv", "run-info.1.csv", "run-info.12.csv", "..",           "a/b",              "../x",         ".hidden",      std::string(300, 'a'),
                                 "x\\\\y",         ""};
    for (const auto& name : names) {
        kt::TempDir dir;
        auto r = sandbox_test::run_script_limited(dir, "local rs = require 'rollsense'\nrs.write_output('" + name +
                                                           "', 'x')\n");
        INFO(name << " -> " << r.text);
        CHECK_THAT(r.text, Catch::StartsWith("invalid argument"));
    }
    kt::TempDir dir;
    auto r = sandbox_test::run_script_limited(dir, "local rs = require 'rollsense'\nrs.write_output('notes.txt', 'x')\n"
                                                   "rs.write_output('run-info.0.csv', 'x')\nrs.write_output('run-info.x.csv', 'x')\n");
    CHECK(r.text == "ok");  // not an earlier run's record: N counts from 1, digits only
}

// Sandbox review: a NUL byte cut a name short, so another file than the one named was written or loaded; and a link
// placed in the run's folder beforehand to a FIFO or a device was written through.
TEST_CASE("a name holding a NUL byte is refused, and rs.write_output does not write through a link to a pipe",
          "[sandbox][names]") {
    const std::pair<std::string, std::string> calls[] = {
        {"rs.write_output('ok.txt\\0/../../nul.txt', 'x')", "output name"},
        {"rs.trial{ object = 'C1', speed = 10, repetition = 1, id = 'ok\\0../../x' }", "option 'id' holds a NUL byte"},
        {"require('lib.helper\\0/../../x')", "module name"}};
    for (const auto& [call, says] : calls) {
        kt::TempDir dir;
        kt::write_file(dir / "lib" / "helper.lua", "return { x = 7 }\n");
        auto r = sandbox_test::run_script_limited(dir, "local rs = require 'rollsense'\n" + call + "\n");
        INFO(call << " -> " << r.text);
        CHECK_THAT(r.text, Catch::Contains(says));
        CHECK_FALSE(kt::fs::exists(dir / "out" / "ok.txt"));
    }
    kt::TempDir dir;
    kt::fs::create_directories(dir / "out");
    REQUIRE(::mkfifo((dir / "pipe").c_str(), 0600) == 0);
    kt::fs::create_symlink(dir / "pipe", dir / "out" / "notes.txt");
    auto r = sandbox_test::run_script_limited(dir, "local rs = require 'rollsense'\nrs.write_output('notes.txt', 'x')\n");
    CHECK_THAT(r.text, Catch::StartsWith("invalid argument") &&
                           Catch::Contains("notes.txt leads to a pipe, a device or a socket; a script writes files into "
                                           "the run's folder only"));
}

TEST_CASE("rs.analyse refuses a model name that is one of the dataset's files, before any work", "[sandbox][names]") {
    for (const char* name : {"manifest.csv", "features.csv", "evaluation.json", "../model.rsm", "trials/x.rsm"}) {
        kt::TempDir dir;
        auto r = sandbox_test::run_script_limited(
            dir, std::string("local rs = require 'rollsense'\nrs.analyse{ model = '") + name + "' }\n");
        INFO(name << " -> " << r.text);
        CHECK_THAT(r.text, Catch::Contains("model") && Catch::Contains(name));
        CHECK_THAT(r.text, Catch::Contains("cannot") || Catch::Contains("must be"));
        CHECK_FALSE(kt::fs::exists(dir / "out" / "features.csv"));
    }
}

TEST_CASE("require finds only plain dotted module names under the allowed roots", "[sandbox][require]") {
    // A module outside every root, at a path made only of identifier characters.
    const auto outside = kt::fs::temp_directory_path() / ("rs_evil_" + std::to_string(::getpid()));
    kt::fs::create_directories(outside);
    kt::write_file(outside / "evil.lua", "return 'escaped'\n");
    std::string dotted;
    for (const auto& part : outside) {
        if (part == "/") continue;
        dotted += "." + part.string();
    }
    const std::string names[] = {dotted + ".evil", "..evil", "a..b", "a.", "1abc", "a-b", std::string(300, 'a')};
    for (const auto& name : names) {
        kt::TempDir dir;
        auto r = sandbox_test::run_script_limited(dir, "return require('" + name + "')\n");
        INFO(name << " -> " << r.text);
        CHECK_THAT(r.text, Catch::Contains("module name"));
    }
    kt::fs::remove_all(outside);

    kt::TempDir dir;
    kt::write_file(dir / "lib" / "helper.lua", "return { x = 7 }\n");
    auto r = sandbox_test::run_script_limited(dir, "assert(require('lib.helper').x == 7)\n");
    CHECK(r.text == "ok");
}
