// Bad input named once, with its place and the way out (review s8): a
// --plugin-path that is no folder, a damaged plugin file that would shadow an
// installed one, a file the loader refuses (dlopen's reason alone), a trial
// file the manifest lists but trials/ lacks.
#include <catch2/catch.hpp>

#include <algorithm>

#include "cli_helpers.hpp"

using namespace rollsense::testing;
namespace fs = std::filesystem;

namespace {
const std::string kDemo = std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/demo_roll.lua";

// A copy of the built plugin `file` in `dir`, cut to half its size.
fs::path damaged_copy(const fs::path& dir, const std::string& file) {
    const fs::path whole = fs::path(ROLLSENSE_PLUGIN_DIR) / file;
    fs::create_directories(dir);
    fs::copy_file(whole, dir / file);
    fs::resize_file(dir / file, fs::file_size(whole) / 2);
    return dir / file;
}
// Four trials of the stock script into `ds` (it records only the trials not yet
// on disk, so the same command resumes).
std::string record_four_trials(const fs::path& ds) {
    return "run " + std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/paper_experiment.lua --seed 11 --set runs=2 " +
           "--set objects=C1,P1 --set speeds=10 --set analyse=false --no-progress -q --out " + ds.string();
}
// Runs the script `lines` (after `local rs = require 'rollsense'`), written as dir/NAME, on the simulated hand into
// dir/out.
CommandRun run_lines(const TempDir& dir, const std::string& name, const std::string& lines, const std::string& options = "") {
    write_file(dir / name, "local rs = require 'rollsense'\n" + lines);
    return run_rollsense("run " + shell_quoted(dir / name) + options + " --no-progress --out " + shell_quoted(dir / "out"));
}
}  // namespace

// Item 1: the folder was searched, found empty, and the command went on with the installed plugins.
TEST_CASE("a --plugin-path that is not a folder is a usage error (2) of every command, before anything runs") {
    TempDir dir("rollsense-cli-plugin-path");
    write_file(dir / "a-file", "x");
    const std::string nowhere = (dir / "nowhere").string(), file = (dir / "a-file").string();
    for (const std::string& command :
         {"run " + kDemo + " --profile mock --out " + shell_quoted(dir / "out"), std::string("evaluate features.csv"),
          std::string("train features.csv -o m.rsm"), "report " + dir.path().string(), std::string("predict m.rsm t.csv"),
          std::string("plugins")}) {
        INFO(command);
        const auto missing = run_rollsense(command + " --plugin-path " + nowhere);
        INFO(missing.output);
        CHECK(missing.status == 2);
        CHECK(count_of(missing.output, "--plugin-path " + nowhere + ": no such folder (give an existing folder, or "
                                                                    "leave the option out)") == 1);
        const auto not_folder = run_rollsense(command + " --plugin-path=" + file);
        INFO(not_folder.output);
        CHECK(not_folder.status == 2);
        CHECK(count_of(not_folder.output, "--plugin-path " + file + ": not a folder") == 1);
    }
    CHECK_FALSE(fs::exists(dir / "out"));  // run stopped before its output folder
    CHECK(run_rollsense("plugins --plugin-path " + dir.path().string()).status == 0);  // an existing folder is fine
}

// Item 2: `rollsense plugins` listed it as FAILED, but run and evaluate used the installed one in silence.
TEST_CASE("a damaged plugin file that shadows an installed one is named once by run and evaluate") {
    TempDir dir("rollsense-cli-damaged");
    const auto actuator = damaged_copy(dir / "plugins", "librollsense_mock_actuator.so");
    const auto run = run_rollsense("run " + kDemo + " --profile mock --no-progress --plugin-path " +
                                   shell_quoted(dir / "plugins") + " --out " + shell_quoted(dir / "ds"));
    INFO(run.output);
    CHECK(run.status == 0);
    CHECK(count_of(run.output, actuator.string() + " is not used: truncated: ") == 1);
    CHECK(count_of(run.output, "Plugin 'mock_actuator' comes from ") == 1);

    const auto classifier = damaged_copy(dir / "plugins", "librollsense_bagged_trees.so");
    const auto features = run_rollsense("features " + shell_quoted(dir / "ds") + " -o " + shell_quoted(dir / "f.csv"));
    REQUIRE(features.status == 0);
    const auto evaluate = run_rollsense("evaluate " + shell_quoted(dir / "f.csv") + " --classifier bagged_trees " +
                                        "--folds 2 --repeats 1 --plugin-path " + shell_quoted(dir / "plugins"));
    INFO(evaluate.output);
    CHECK(count_of(evaluate.output, classifier.string() + " is not used: truncated: ") == 1);
    CHECK(count_of(evaluate.output, "Plugin 'bagged_trees' comes from ") == 1);
    CHECK(count_of(evaluate.output, "mock_actuator") == 0);  // not used here: not mentioned
}

// Review (cli item 3): a file dlopen refused was listed with Boost.DLL's wording around
// dlerror()'s text and an errno message unrelated to it ("... : Bad file descriptor").
TEST_CASE("rollsense plugins lists a file the loader refuses with dlopen's reason alone and the way out") {
    TempDir dir("rollsense-cli-plugin-refused");
    const fs::path needs = dir / "librollsense_needs_dependency.so", text = dir / "librollsense_text.so";
    fs::copy_file(ROLLSENSE_TEST_MISSING_DEPENDENCY, needs);
    write_file(text, "this is text, not a library\n");
    const auto r = run_rollsense("plugins --plugin-path " + shell_quoted(dir.path()));
    INFO(r.output);
    CHECK(r.status == 0);
    CHECK(count_of(r.output, "FAILED " + needs.string() + "\n      cannot be loaded: librollsense_test_dependency.so: "
                             "cannot open shared object file: No such file or directory (a library it needs: `ldd " +
                             needs.string() + "` shows which is missing; install it or add its folder to "
                             "LD_LIBRARY_PATH)\n") == 1);
    CHECK(count_of(r.output, "FAILED " + text.string() + "\n      cannot be loaded: " + text.string() +
                             ": file too short (rebuild or reinstall it, or remove it from the search path)\n") == 1);
    for (const char* noise : {"boost::dll", "dlerror", "Bad file descriptor", "Success"}) {
        INFO(noise);
        CHECK(r.output.find(noise) == std::string::npos);
    }
}

// Item 4: "points at missing file" named neither the manifest's line nor a way out.
TEST_CASE("a trial file missing from trials/ is named with its manifest line and the way out by every reader") {
    TempDir dir("rollsense-cli-missing-trial");
    const fs::path ds = dir / "ds";
    const std::string record = record_four_trials(ds);
    REQUIRE(run_rollsense(record).status == 0);
    const std::string manifest = read_file(ds / "manifest.csv");
    const auto second = manifest.find('\n', manifest.find('\n') + 1) + 1;  // line 3
    const std::string id = manifest.substr(second, manifest.find(',', second) - second);
    const std::string trial_file = read_file(ds / "trials" / (id + ".csv"));
    fs::remove(ds / "trials" / (id + ".csv"));
    const std::string expected = (ds / "manifest.csv").string() + ":3: trial '" + id + "' is listed, but " +
                                 (ds / "trials" / (id + ".csv")).string() +
                                 " is missing. Put the file back, record it again in its place with 'rollsense "
                                 "run SCRIPT --out " + ds.string() + " --resume', or delete line 3 of manifest.csv "
                                 "to use the dataset without that trial";
    for (const std::string& command : {"features " + ds.string() + " -o " + (dir / "f.csv").string(),
                                       "evaluate " + ds.string() + " --folds 2", "report " + ds.string(),
                                       "train " + ds.string() + " -o " + (dir / "m.rsm").string()}) {
        INFO(command);
        const auto r = run_rollsense(command);
        INFO(r.output);
        CHECK(r.status == 3);
        CHECK(count_of(r.output, expected) == 1);
    }
    // Each way out works. Resume records the trial again, the same bytes in the same
    // place of the manifest (it refused the dataset before: "cannot resume").
    const auto in_place = run_rollsense(record + " --resume");
    INFO(in_place.output);
    CHECK(in_place.status == 0);
    CHECK(count_of(in_place.output, "trial '" + id + "' is recorded again") == 1);
    CHECK(read_file(ds / "trials" / (id + ".csv")) == trial_file);
    CHECK(read_file(ds / "manifest.csv") == manifest);
    // Without its manifest row the dataset reads, and resume records the trial again.
    fs::remove(ds / "trials" / (id + ".csv"));
    std::string without = manifest;
    const auto row = without.find("\n" + id + ",") + 1;
    without.erase(row, without.find('\n', row) + 1 - row);
    write_file(ds / "manifest.csv", without);
    CHECK(run_rollsense("features " + ds.string() + " -o " + (dir / "f.csv").string()).status == 0);
    const auto resumed = run_rollsense(record + " --resume");
    INFO(resumed.output);
    CHECK(resumed.status == 0);
    CHECK(fs::exists(ds / "trials" / (id + ".csv")));
    CHECK(read_file(ds / "manifest.csv").find("\n" + id + ",") != std::string::npos);
}

// Review: a manifest.csv that is a folder gave "unexpected error:
// basic_filebuf::underflow error reading the file: Is a directory", exit 1,
// from every command that reads a dataset; a dataset-info.csv or trial file
// that is a folder already gave "...: is a folder, not a CSV file", exit 3.
TEST_CASE("a manifest.csv that is a folder is named by every reader of the dataset (3)") {
    TempDir dir("rollsense-cli-manifest-folder");
    const fs::path ds = dir / "ds";
    const std::string record = record_four_trials(ds);
    REQUIRE(run_rollsense(record).status == 0);
    const std::string model = (dir / "m.rsm").string();
    REQUIRE(run_rollsense("train " + ds.string() + " --set learners=3 -o " + model).status == 0);
    fs::remove(ds / "manifest.csv");
    fs::create_directory(ds / "manifest.csv");
    const std::string expected = (ds / "manifest.csv").string() + ": is a folder, not a CSV file";
    for (const std::string& command :
         {"features " + ds.string() + " -o " + (dir / "f.csv").string(), "evaluate " + ds.string() + " --folds 2",
          "report " + ds.string(), "train " + ds.string() + " -o " + (dir / "m2.rsm").string(),
          "predict " + model + " " + ds.string(), "view " + ds.string() + " --port 0 --for 0.1"}) {
        INFO(command);
        const auto r = run_rollsense(command);
        INFO(r.output);
        CHECK(r.status == 3);
        CHECK(count_of(r.output, expected) == 1);
        CHECK(r.output.find("unexpected error") == std::string::npos);
    }
    const auto resumed = run_rollsense(record + " --resume");
    INFO(resumed.output);
    CHECK(resumed.status == 3);
    CHECK(count_of(resumed.output, expected) == 1);
}

// Found checking the readers of the review's finding above: --resume refused a
// run-config.csv that is a folder as a bad command line (2), though the command
// line was right and the dataset's file is wrong.
TEST_CASE("a run-config.csv that is a folder is named by --resume as the dataset's error (3)") {
    TempDir dir("rollsense-cli-run-config-folder");
    const fs::path ds = dir / "ds";
    REQUIRE(run_rollsense(record_four_trials(ds)).status == 0);
    fs::remove(ds / "run-config.csv");
    fs::create_directory(ds / "run-config.csv");
    const auto r = run_rollsense(record_four_trials(ds) + " --resume");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "cannot resume: " + (ds / "run-config.csv").string() + ": is a folder, not a CSV file") == 1);
}

// User review (Lua scripts): --resume into a folder that does not exist (a path mistyped after a crash) recorded the
// whole run again there, without a word; the stopped dataset stayed half done.
TEST_CASE("a resume into a folder that does not exist is a usage error (2) that records nothing") {
    TempDir dir("rollsense-cli-resume-missing");
    const fs::path typo = dir / "dss";
    const auto r = run_rollsense(record_four_trials(typo) + " --resume");
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK(count_of(r.output, "--resume: " + typo.string() + " does not exist: there is no dataset to continue") == 1);
    CHECK_FALSE(fs::exists(typo));
    // An existing folder, empty (a run stopped before its first file), still resumes: a requeued shard's case.
    fs::create_directory(typo);
    CHECK(run_rollsense(record_four_trials(typo) + " --resume").status == 0);
    CHECK(fs::exists(typo / "manifest.csv"));
}

// User review (sharded runs): `--shard ''` (a batch script's unset variable) recorded the whole run, `--seed ''` took
// the default seed, and an option given twice kept the last (submit.sh's SCRIPT --out X gave each shard two --out).
TEST_CASE("an option with an empty value, or a single option given twice, is a usage error (2) that records nothing") {
    TempDir dir("rollsense-cli-option-twice");
    const fs::path out = dir / "ds";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {" --shard ''", "option --shard has an empty value (an unset shell variable?): give a value, or leave the option out"},
        {" --seed ''", "option --seed has an empty value"},
        {" --profile=", "option --profile has an empty value"},
        {" --seed 3", "option --seed is given 2 times ('11' and '3'): give it once"},  // 11: record_four_trials
        {" --out " + (dir / "other").string(), "option --out is given 2 times"}};
    for (const auto& [extra, says] : cases) {
        INFO(extra);
        const auto r = run_rollsense(record_four_trials(out) + extra);
        INFO(r.output);
        CHECK(r.status == 2);
        CHECK(count_of(r.output, says) == 1);
        CHECK_FALSE(fs::exists(out));
        CHECK_FALSE(fs::exists(dir / "other"));
    }
    REQUIRE(run_rollsense(record_four_trials(out)).status == 0);
    const auto report = run_rollsense("report " + out.string() + " -o a.html --output b.html");
    CHECK(report.status == 2);
    CHECK(count_of(report.output, "option --output (-o) is given 2 times") == 1);
}

// The dynamixel plugin's refusals of its parameters named neither the profile
// file nor the parameter ("'baud' 1000001 is not ..."), and a position-mode joint's
// max beyond one turn only warned at activation: both are the profile's error (3),
// named once with the file, the parameter and the way out, before anything moves.
TEST_CASE("a dynamixel profile the plugin refuses is named once by file and parameter, with the way out (3)") {
    TempDir dir("rollsense-cli-dxl-profile");
    const std::string profile = (dir / "rig.lua").string();
    for (auto [change, expected] :
         {std::pair{"hand.params.max = { 200, 60, 110, 300 }",
                    ": devices.hand.params.max: joint 'sensing_finger' (id 1): 200 deg is servo tick 4324, beyond "
                    "the one turn a servo reaches in position mode"},
          std::pair{"hand.params.baud = 1000001", ": devices.hand.params.baud: 1000001 is not a Dynamixel baud rate"},
          std::pair{"hand.params.max_current = { 400, 400, 4000, 300 }",
                    ": devices.hand.params.max_current: joint 'palm' (id 3): 4000 mA is above"}}) {
        INFO(change);
        write_file(dir / "rig.lua", std::string("local p = include('etroll-virtual')\nlocal hand = p.devices.hand\n") +
                                        change + "\nreturn p\n");
        const auto r = run_rollsense("run " + kDemo + " --profile " + shell_quoted(dir / "rig.lua") + " --out " +
                                     shell_quoted(dir / "out"));
        INFO(r.output);
        CHECK(r.status == 3);
        CHECK(count_of(r.output, profile + expected) == 1);
        CHECK(count_of(r.output, profile) == 1);
    }
}

// Review (plugin author) item 5: `plugins --check` passed a schema that contradicts itself.
TEST_CASE("rollsense plugins --check fails on a schema that declares a parameter twice or a default its range refuses") {
    const auto fault = [](const char* which) {
        return run_rollsense("plugins --check --plugin-path " + shell_quoted(std::string(ROLLSENSE_TEST_BAD_SCHEMA_DIR) + which));
    };
    const auto out_of_range = fault("default");
    INFO(out_of_range.output);
    CHECK(out_of_range.status == 3);
    CHECK(count_of(out_of_range.output, "SCHEMA FAILED: plugin 'bad_schema': its schema is wrong: a default its own "
                                        "declaration refuses: key 'gain': 5 is outside the allowed range [0, 1] (fix the "
                                        "plugin's schema function)\n") == 1);
    const auto twice = fault("twice");
    INFO(twice.output);
    CHECK(twice.status == 3);
    CHECK(count_of(twice.output, "SCHEMA FAILED: plugin 'bad_schema': its schema is wrong: parameter 'gain' is declared "
                                 "twice") == 1);
    // Review (plugins): a range no value fits, and a name --set and --classifier entries cannot spell, passed --check.
    const auto empty_range = fault("empty_range");
    CHECK(empty_range.status == 3);
    CHECK(count_of(empty_range.output, "its schema is wrong: parameter 'gain': its range [min, max] is empty") == 1);
    const auto bad_name = fault("bad_name");
    CHECK(bad_name.status == 3);
    CHECK(count_of(bad_name.output, "its schema is wrong: parameter 'the gain': a name is a-z, 0-9 and _") == 1);
    // A run refuses it too (review: it used the schema that --check refused), before anything moves.
    TempDir dir("rollsense-cli-bad-schema");
    write_file(dir / "rig.lua", "local p = include('mock')\np.devices.tactile = { plugin = 'bad_schema' }\nreturn p\n");
    const auto run = run_rollsense("run " + kDemo + " --profile " + shell_quoted(dir / "rig.lua") + " --plugin-path " +
                                   shell_quoted(std::string(ROLLSENSE_TEST_BAD_SCHEMA_DIR) + "twice") + " --out " +
                                   shell_quoted(dir / "out"));
    INFO(run.output);
    CHECK(run.status == 3);
    CHECK(count_of(run.output, "plugin 'bad_schema': its schema is wrong: parameter 'gain' is declared twice") == 1);
    CHECK(run.output.find("devices.tactile: plugin 'bad_schema'") != std::string::npos);  // review (plugins): no device named
    // Without --check the listing goes on (exit 0); the shipped plugins' schemas have no such mistake.
    CHECK(run_rollsense("plugins --plugin-path " + shell_quoted(std::string(ROLLSENSE_TEST_BAD_SCHEMA_DIR) + "twice")).status == 0);
    const auto shipped = run_rollsense("plugins --check");
    INFO(shipped.output);
    CHECK(shipped.status == 0);
    CHECK(shipped.output.find("SCHEMA FAILED") == std::string::npos);

    // User review (out-of-tree plugins): a string parameter's choices were shown only by the error of a wrong one.
    const auto params = run_rollsense("plugins --params");
    CHECK(params.output.find("split_criterion        string           = 'gdi' one of 'gdi', 'deviance', 'twoing'\n") !=
          std::string::npos);

    // User review (out-of-tree plugins): a build's copy given with --plugin-path, its namesake also installed (the
    // docs' workflow), failed --check; the installed copy is unused, by the search order, not a failure.
    TempDir over("rollsense-cli-plugins-override");
    const std::string installed = std::string(ROLLSENSE_BIN_DIR) + "/../lib/rollsense/plugins/librollsense_example_bump.so";
    std::filesystem::copy_file(installed, over / "librollsense_example_bump.so");
    const auto overriding = run_rollsense("plugins --check --plugin-path " + shell_quoted(over.path()));
    INFO(overriding.output);
    CHECK(overriding.status == 0);
    CHECK(count_of(overriding.output, "  unused ") == 1);
    CHECK(overriding.output.find("FAILED") == std::string::npos);
    // Two copies in one folder are a mistake: which one runs depends on their names.
    std::filesystem::copy_file(installed, over / "librollsense_example_bump2.so");
    // Written with a trailing '/' too (diff review: the folder was then taken for an earlier one, and passed).
    const auto two_copies = run_rollsense("plugins --check --plugin-path " + shell_quoted(over.path().string() + "/"));
    INFO(two_copies.output);
    CHECK(two_copies.status == 3);
    CHECK(count_of(two_copies.output, "FAILED " + (over / "librollsense_example_bump2.so").string() + "\n      shadowed: a "
                                 "plugin named 'example_bump' was already found at " +
                                 (over / "librollsense_example_bump.so").string() + ", in the same folder") == 1);
}

// Review: a plugin whose static initialiser throws ended `plugins` with "unexpected error" naming no file, and a
// run that went on after it hung (the unwind out of dlopen leaves the loader's lock held).
TEST_CASE("a plugin whose static initialiser throws stops the process with its file named") {
    TempDir dir("rollsense-cli-static-thrower");
    const std::string path = " --plugin-path " + shell_quoted(std::string(ROLLSENSE_TEST_STATIC_THROWER_DIR));
    const auto listing = run_rollsense("plugins" + path);
    INFO(listing.output);
    const auto run = run_rollsense("run " + kDemo + path + " --no-progress --out " + shell_quoted(dir / "out"));
    INFO(run.output);
    CHECK_FALSE(fs::exists(dir / "out" / "manifest.csv"));
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer's dlopen interceptor has no unwind path: there the exception ends in std::terminate (134),
    // still before anything runs, without the file's name.
    CHECK(listing.status == 134);
    CHECK(run.status == 134);
    CHECK(count_of(listing.output, "static initialisation failed") == 1);
    CHECK(count_of(run.output, "std::terminate") == 1);
    return;
#endif
    CHECK(listing.status == 3);
    CHECK(count_of(listing.output, "librollsense_test_static_thrower.so: its static initialisation threw an "
                                   "exception") == 1);
    CHECK(listing.output.find("unexpected error") == std::string::npos);
    CHECK(run.status == 3);
    CHECK(count_of(run.output, "fix the plugin or remove it from the search path") == 1);
}

// Review (scripting): after rs.trial was refused (an object the sim does not know), the trial stayed open, and a
// recording of it was saved into the manifest.
TEST_CASE("a trial the devices refused is not open: nothing of it is recorded or saved") {
    TempDir dir("rollsense-cli-refused-trial");
    const auto r = run_lines(dir, "ghost.lua", "print(pcall(rs.trial, { object = 'ZZ', speed = 10, repetition = 1 }))\n"
                                               "rs.record_start()\n");
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(count_of(r.output, "ghost.lua:3: recording needs a trial") == 1);
    CHECK(read_file(dir / "out" / "manifest.csv").find("ZZ") == std::string::npos);
}

// Review (scripting): a recording never stopped grew by 45 MB a second until the machine ran out of memory.
TEST_CASE("a recording is bounded by the script's memory cap, and the run ends naming the trial") {
    TempDir dir("rollsense-cli-endless-recording");
    const auto r = run_lines(dir, "forever.lua", "rs.trial{ object = 'C2', speed = 10, repetition = 1 }\n"
                                                 "rs.record_start()\n"
                                                 "rs.wait_until(function() return false end)\n",
                             " --memory-limit-mb 4");
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(count_of(r.output, "trial 'C2-v10-r001': its recording reached the memory cap (--memory-limit-mb) after ") == 1);
}

// Review (scripting): rs.log wrote an 11 MB line, and a line break let a script print a line that looked like the
// program's own error.
TEST_CASE("a script's log entry is cut at 64 KiB and its line breaks are indented, print's too") {
    TempDir dir("rollsense-cli-log-entry");
    const auto r = run_lines(dir, "log.lua", "rs.log(string.rep('L', 200000))\n"
                                             "rs.warn('first\\nerror   rollsense: not the program')\n"
                                             "print('second\\rerror   rollsense: not the program either', "
                                             "string.rep('P', 70000))\n");
    INFO(r.output.substr(0, 2000));
    CHECK(r.status == 0);
    CHECK(count_of(r.output, std::string(65536, 'L') + " ... (cut at 64 KiB)\n") == 1);
    CHECK(count_of(r.output, std::string(65537, 'L')) == 0);
    CHECK(count_of(r.output, "first\n  error   rollsense: not the program") == 1);
    CHECK(count_of(r.output, "second\\rerror   rollsense: not the program either\t" + std::string(100, 'P')) == 1);
    CHECK(count_of(r.output, std::string(65536, 'P')) == 0);
}

// A profile's content error was printed as a "parse error" with the file alone ("mock.lua: sample_rate_hz and
// control_rate_hz must be > 0"): now once, as a bad profile, at the key's file:line with the way out, exit 3.
TEST_CASE("a profile whose content is wrong is named once by file:line and key, as a bad profile (3)") {
    TempDir dir("rollsense-cli-bad-profile");
    std::string mock = read_file(fs::path(ROLLSENSE_SOURCE_DIR) / "share/profiles/mock.lua");
    const auto at = mock.find("sample_rate_hz = 31.1");
    REQUIRE(at != std::string::npos);
    const int line = 1 + static_cast<int>(std::count(mock.begin(), mock.begin() + static_cast<long>(at), '\n'));
    write_file(dir / "mock.lua", mock.replace(at, 21, "sample_rate_hz = -5"));
    const auto r = run_rollsense("run " + kDemo + " --profile " + shell_quoted(dir / "mock.lua") + " --no-progress --out " +
                                 shell_quoted(dir / "out"));
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "bad profile: " + (dir / "mock.lua").string() + ":" + std::to_string(line) +
                                 ": sample_rate_hz = -5: must be > 0 (the sensors' sample rate in Hz)") == 1);
    CHECK(count_of(r.output, "must be > 0") == 1);
    CHECK(r.output.find("parse error") == std::string::npos);
    CHECK_FALSE(fs::exists(dir / "out"));
}
