// `rollsense predict` end to end on a tiny stock run (runs=1, seed 11):
// record, extract features, train, then classify the recordings, a single
// trial file, a trial without clean peaks and trials unlike the training data.
#include <sys/stat.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>

#include "cli_helpers.hpp"

namespace {
using namespace rollsense::testing;
namespace fs = std::filesystem;

// The run, its features.csv and model trained.rsm, made once for every test
// case of this file (built in a temporary folder, then renamed into place, so
// parallel test processes never see half of it).
fs::path fixture() {
    const fs::path done = fs::path(ROLLSENSE_BINARY_DIR) / "tests" / "cli-predict-run11";
    std::error_code ec;
    if (fs::exists(done / "trained.rsm", ec)) return done;
    TempDir work("rollsense-cli-predict");
    const fs::path run = work / "run";
    const auto rec = run_rollsense("run " + shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "paper_experiment.lua") + " --set runs=1 --set analyse=false --seed 11 --no-progress -q --out " +
                                   shell_quoted(run));
    INFO(rec.output);
    REQUIRE(rec.status == 0);
    REQUIRE(run_rollsense("features " + shell_quoted(run) + " -o " + shell_quoted(run / "features.csv")).status == 0);
    const auto train = run_rollsense("train " + shell_quoted(run / "features.csv") + " -o " + shell_quoted(run / "trained.rsm"));
    INFO(train.output);
    REQUIRE(train.status == 0);
    fs::create_directories(done.parent_path());
    fs::rename(run, done, ec);  // another process may have won the race: either copy is the same
    return done;
}

// A copy of the run's dataset (no model, no features) to alter.
fs::path copy_dataset(const fs::path& from, const fs::path& to) {
    fs::create_directories(to / "trials");
    for (const char* f : {"dataset-info.csv", "manifest.csv"}) fs::copy_file(from / f, to / f);
    for (const auto& e : fs::directory_iterator(from / "trials")) fs::copy_file(e.path(), to / "trials" / e.path().filename());
    return to;
}

// Multiplies the channel columns (1..3) of a trial file by `factor`.
void scale_channels(const fs::path& trial, double factor) {
    std::istringstream in(read_file(trial));
    std::string out, line;
    std::getline(in, line);
    out += line + "\n";
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
        for (std::size_t c = 1; c <= 3 && c < f.size(); ++c) {
            std::ostringstream v;
            v.precision(9);
            v << std::stod(f[c]) * factor;
            f[c] = v.str();
        }
        for (std::size_t i = 0; i < f.size(); ++i) out += (i ? "," : "") + f[i];
        out += "\n";
    }
    write_file(trial, out);
}

std::size_t manifest_trials(const fs::path& dataset) {
    std::istringstream in(read_file(dataset / "manifest.csv"));
    std::size_t n = 0;
    for (std::string l; std::getline(in, l);) n += !l.empty();
    return n - 1;
}

}  // namespace

TEST_CASE("predict classifies every trial of a dataset with the trained model") {
    const fs::path run = fixture();
    const auto r = run_rollsense("predict " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(run));
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(r.output.find("trial") == 0);
    CHECK(r.output.find("C1-v10-r001") != std::string::npos);
    // Trained on these very trials and checked against them: no warning.
    CHECK(r.output.find("warning") == std::string::npos);
    // The runner-up's score as the class's, three decimals, and none when no other class scored (first-day review:
    // "C2 0.4", and "C1 0" naming an arbitrary class).
    std::istringstream lines(r.output);
    std::string line;
    std::getline(lines, line);  // the header
    while (std::getline(lines, line)) {
        if (line.find("no decision: ") != std::string::npos) continue;
        INFO(line);
        CHECK(std::regex_search(line, std::regex(R"( \d\.\d{3}  ([A-Z]\w* \d\.\d{3}|-)$)")));
        CHECK_FALSE(std::regex_search(line, std::regex(R"( 0\.000$)")));
    }
    CHECK(r.output.find("not checked") == std::string::npos);

    const auto j = run_rollsense("predict --json " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(run) + " 2>/dev/null");
    REQUIRE(j.status == 0);
    CHECK(j.output.front() == '[');
    CHECK(count_of(j.output, "\"trial_id\"") == manifest_trials(run));
    CHECK(count_of(j.output, "\"warnings\": []") == manifest_trials(run));
    // Scores name the model's classes.
    CHECK(std::regex_search(j.output, std::regex(R"("scores": \{\s*"C1": )")));
}

TEST_CASE("predict takes one trial file, and a trial without clean peaks gets no decision with the reason") {
    const fs::path run = fixture();
    TempDir dir("rollsense-cli-predict");
    const fs::path ds = copy_dataset(run, dir / "ds");
    const auto one = run_rollsense("predict " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(ds / "trials" / "C2-v15-r001.csv"));
    INFO(one.output);
    REQUIRE(one.status == 0);
    CHECK(count_of(one.output, "-v") == 1);  // the one trial only
    CHECK(one.output.find("C2-v15-r001") != std::string::npos);

    scale_channels(ds / "trials" / "C2-v15-r001.csv", 0.0);
    const auto flat = run_rollsense("predict --json " + shell_quoted(run / "trained.rsm") + " " +
                                    shell_quoted(ds / "trials" / "C2-v15-r001.csv"));
    INFO(flat.output);
    REQUIRE(flat.status == 0);
    CHECK(flat.output.find("\"class\": null") != std::string::npos);
    CHECK(flat.output.find("low_amplitude") != std::string::npos);

    // Review (bad input) item 7: a named trial file that cannot be read gave exit 0 and "no decision".
    const std::string text = read_file(ds / "trials" / "C2-v15-r001.csv");
    const auto fifth = text.find('\n', text.find('\n', text.find('\n', text.find('\n') + 1) + 1) + 1);
    write_file(ds / "trials" / "C2-v15-r001.csv", text.substr(0, fifth + 1) + "0.5,1\n" + text.substr(text.find('\n', fifth + 1) + 1));
    const auto torn = run_rollsense("predict " + shell_quoted(run / "trained.rsm") + " " +
                                    shell_quoted(ds / "trials" / "C2-v15-r001.csv"));
    INFO(torn.output);
    CHECK(torn.status == 3);
    CHECK(torn.output.find("C2-v15-r001.csv:5: 2 fields") != std::string::npos);
    CHECK(torn.output.find("restore the file, or record the trial again") != std::string::npos);
    CHECK(torn.output.find("no decision") == std::string::npos);
}

TEST_CASE("predict warns when the input is unlike the training data") {
    const fs::path run = fixture();
    TempDir dir("rollsense-cli-predict");
    const fs::path ds = copy_dataset(run, dir / "ds");
    // Another sample rate...
    std::string info = read_file(ds / "dataset-info.csv");
    info = std::regex_replace(info, std::regex("sample_rate_hz,[0-9.]+"), "sample_rate_hz,100");
    write_file(ds / "dataset-info.csv", info);
    // ...and ten times the pressure: amplitude features far outside training's.
    scale_channels(ds / "trials" / "C1-v10-r001.csv", 10.0);
    const auto r = run_rollsense("predict " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(ds / "trials" / "C1-v10-r001.csv"));
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(r.output.find("warning: sample rate 100 Hz differs from training's 31.1 Hz") != std::string::npos);
    CHECK(r.output.find("outside the training range") != std::string::npos);

    // Without the training run's files beside the model, what is not checked is said.
    fs::copy_file(run / "trained.rsm", dir / "alone.rsm");
    const auto alone = run_rollsense("predict " + shell_quoted(dir / "alone.rsm") + " " + shell_quoted(run));
    CHECK(alone.status == 0);
    CHECK(alone.output.find("not checked against the training data") != std::string::npos);
    CHECK(alone.output.find("feature ranges not checked") != std::string::npos);
    // --training names them.
    const auto named = run_rollsense("predict --training " + shell_quoted(run) + " " + shell_quoted(dir / "alone.rsm") + " " + shell_quoted(run));
    CHECK(named.output.find("not checked") == std::string::npos);
}

// Review (data): a dataset that does not say which three channels identify the object got "no decision" with that
// reason on every trial, exit 0; the dataset's fault is now said once, as a bad input (3).
TEST_CASE("predict refuses a dataset whose identification channels are not known, once") {
    const fs::path run = fixture();
    TempDir dir("rollsense-cli-predict-channels");
    const fs::path ds = copy_dataset(run, dir / "ds");
    std::string info = read_file(ds / "dataset-info.csv");
    info = std::regex_replace(info, std::regex("\nchannels,[^\n]*"), "\nchannels,ch1 ch2 ch3 ch4");
    info = std::regex_replace(info, std::regex("\nchannel_units,[^\n]*"), "\nchannel_units,1 1 1 1");
    write_file(ds / "dataset-info.csv", info);
    const auto r = run_rollsense("predict " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(ds));
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "does not say which three identify the object") == 1);
    CHECK(r.output.find("no decision") == std::string::npos);
}

TEST_CASE("predict's errors name the model, the plugin and the way out") {
    const fs::path run = fixture();
    TempDir dir("rollsense-cli-predict");
    const auto missing = run_rollsense("predict " + shell_quoted(dir / "none.rsm") + " " + shell_quoted(run));
    CHECK(missing.status == 3);
    CHECK(missing.output.find("none.rsm: no such model file") != std::string::npos);

    // The features table or a trial file given as MODEL is named as such (first-day review: "give --classifier").
    for (const auto& table : std::vector<fs::path>{run / "features.csv", run / "trials" / "C1-v10-r001.csv"}) {
        const auto swapped = run_rollsense("predict " + shell_quoted(table) + " " + shell_quoted(run));
        INFO(swapped.output);
        CHECK(swapped.status == 3);
        CHECK(count_of(swapped.output, table.string() + ":1: a CSV table, not a model: give the model first") == 1);
        CHECK(swapped.output.find("--classifier") == std::string::npos);
    }
    // Without --training, the way to the check is said (first-day review).
    fs::copy_file(run / "trained.rsm", dir / "alone.rsm");
    const auto alone = run_rollsense("predict " + shell_quoted(dir / "alone.rsm") + " " + shell_quoted(run));
    CHECK(alone.status == 0);
    CHECK(count_of(alone.output, "not checked against the training data") == 1);
    CHECK(count_of(alone.output, "give --training DIR, the output folder of the run the model was trained on") == 1);

    write_file(dir / "odd.rsm", "something else\n");
    const auto odd = run_rollsense("predict " + shell_quoted(dir / "odd.rsm") + " " + shell_quoted(run));
    CHECK(odd.status == 3);
    CHECK(odd.output.find("--classifier") != std::string::npos);

    const auto wrong = run_rollsense("predict --classifier no_such_plugin " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(run));
    CHECK(wrong.status == 3);
    CHECK(wrong.output.find("no_such_plugin") != std::string::npos);

    const auto not_trial = run_rollsense("predict " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(run / "features.csv"));
    INFO(not_trial.output);
    CHECK(not_trial.status == 3);  // review: "not found" for a file that exists, and "copy the whole dataset folder"
    CHECK(not_trial.output.find("features.csv is a file of the dataset " + fs::absolute(run).string() +
                                ", not one of its trials; predict takes a trial file") != std::string::npos);
    CHECK(not_trial.output.find("not found") == std::string::npos);
    write_file(dir / "loose.csv", "t,p1\n");
    const auto loose = run_rollsense("predict " + shell_quoted(run / "trained.rsm") + " " + shell_quoted(dir / "loose.csv"));
    CHECK(loose.status == 3);
    CHECK(loose.output.find("trials/ folder") != std::string::npos);

    CHECK(run_rollsense("predict " + shell_quoted(run / "trained.rsm")).status == 2);

    // Review finding 16: a folder or an empty file as MODEL was "does not name its classifier; give --classifier".
    fs::create_directories(dir / "stock");
    fs::copy_file(run / "trained.rsm", dir / "stock" / "model.rsm");
    const auto folder = run_rollsense("predict " + shell_quoted(dir / "stock") + " " + shell_quoted(run));
    INFO(folder.output);
    CHECK(folder.status == 2);  // the arguments swapped: the command line's mistake (first-day review: 3)
    CHECK(folder.output.find("stock is a folder, not a model file; did you mean " + (dir / "stock" / "model.rsm").string() +
                             "?") != std::string::npos);
    CHECK(folder.output.find("--classifier") == std::string::npos);
    write_file(dir / "empty.rsm", "");
    const auto empty = run_rollsense("predict " + shell_quoted(dir / "empty.rsm") + " " + shell_quoted(run));
    INFO(empty.output);
    CHECK(empty.status == 3);
    CHECK(empty.output.find("empty.rsm: the model file is empty") != std::string::npos);
    CHECK(empty.output.find("--classifier") == std::string::npos);

    // Sandbox review: a pipe or a device as the model was read without end (/dev/zero: 1 GB in 18 s; a pipe nobody
    // writes: no end, past Ctrl-C), by predict and by a script's rs.classifier, before any plugin looked at it.
    REQUIRE(::mkfifo((dir / "pipe.rsm").c_str(), 0600) == 0);
    write_file(dir / "load.lua", "local rs = require 'rollsense'\nfor _, m in ipairs({ '/dev/zero', '" +
                                     (dir / "pipe.rsm").string() + "' }) do\n"
                                     "  for _, c in ipairs({ '', 'bagged_trees' }) do\n"
                                     "    local ok, err = pcall(rs.classifier, { model = m, classifier = c ~= '' and c or nil })\n"
                                     "    rs.log(tostring(ok) .. ' ' .. err)\n  end\nend\n");
    for (const std::string& device : {std::string("/dev/zero"), (dir / "pipe.rsm").string()}) {
        const auto r = run_rollsense("predict " + shell_quoted(device) + " " + shell_quoted(run));
        INFO(r.output);
        CHECK(r.status == 2);
        CHECK(count_of(r.output, device + " is not a regular file (a pipe, a socket or a device): give the model file") == 1);
    }
    const auto script = run_rollsense("run " + shell_quoted(dir / "load.lua") + " --profile mock --out " + shell_quoted(dir / "out"));
    INFO(script.output);
    CHECK(script.status == 0);
    CHECK(count_of(script.output, "false /dev/zero is not a regular file") == 2);
    CHECK(count_of(script.output, "false " + (dir / "pipe.rsm").string() + " is not a regular file") == 2);
}

// Review: `--training nosuch` exited 0 with only "not checked ... no
// dataset-info.csv"; `--training` of another dataset blamed every trial
// ("channel set differs", "F1 outside the training range").
TEST_CASE("predict refuses a --training folder that is missing, not a dataset or another dataset (2)") {
    const fs::path run = fixture();
    TempDir dir("rollsense-cli-predict");
    const std::string model = shell_quoted(run / "trained.rsm");
    const std::string trial = shell_quoted(run / "trials" / "C1-v10-r001.csv");

    const auto nosuch = run_rollsense("predict " + model + " " + trial + " --training " + shell_quoted(dir / "nosuch"));
    INFO(nosuch.output);
    CHECK(nosuch.status == 2);
    CHECK(nosuch.output.find("--training " + (dir / "nosuch").string() + ": no such folder") != std::string::npos);

    fs::create_directories(dir / "empty");
    const auto empty = run_rollsense("predict " + model + " " + trial + " --training " + shell_quoted(dir / "empty"));
    INFO(empty.output);
    CHECK(empty.status == 2);
    CHECK(empty.output.find("--training " + (dir / "empty").string() + " is not a dataset folder (it has no dataset-info.csv)") !=
          std::string::npos);

    // Another run, of two of the nine objects: its clean trials are not the model's classes.
    const fs::path other = dir / "other";
    const auto rec = run_rollsense("run " + shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "paper_experiment.lua") +
                                   " --set runs=1 --set objects=C1,P1 --set analyse=false --seed 12 --no-progress -q --out " +
                                   shell_quoted(other));
    REQUIRE(rec.status == 0);
    REQUIRE(run_rollsense("features " + shell_quoted(other) + " -o " + shell_quoted(other / "features.csv")).status == 0);
    const auto wrong = run_rollsense("predict " + model + " " + trial + " --training " + shell_quoted(other));
    INFO(wrong.output);
    CHECK(wrong.status == 2);
    CHECK(wrong.output.find("--training " + other.string() + " is not the dataset " + (run / "trained.rsm").string() +
                            " was trained on: its clean trials are of C1, P1, the model's classes C1, C2, ") !=
          std::string::npos);
    CHECK(wrong.output.find("outside the training range") == std::string::npos);

    // A model beside another dataset (its default --training): that dataset is not used to blame the trials.
    fs::copy_file(run / "trained.rsm", other / "model.rsm");
    const auto beside = run_rollsense("predict " + shell_quoted(other / "model.rsm") + " " + trial);
    INFO(beside.output);
    CHECK(beside.status == 0);
    CHECK(beside.output.find("not checked against the training data, in " + other.string() +
                             ": it holds another dataset (its clean trials are of C1, P1") != std::string::npos);
    CHECK(beside.output.find("warning") == std::string::npos);
}
