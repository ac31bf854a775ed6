// Review fixes, end to end through the program:
//  * rollsense train fits a series classifier (minirocket) on the prepared
//    series, the very model rs.analyse saves with the same options;
//  * a features CSV where the recorded trials are needed (a series classifier,
//    --prefixes) is refused before any work, naming the file, exit 2;
//  * rollsense report on a run's folder never replaces the run's own
//    evaluation unless told (--force), writes beside it under another name
//    (-o report-NAME.html), and by default evaluates with the run's seed;
//  * one repetition: "sd" is null in evaluation.json.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "cli_dataset.hpp"
#include "json_reader.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using rollsense::testing::JsonReader;
using rollsense::testing::run_rollsense;

namespace {

std::string file_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A small simulated run whose script ends with rs.analyse of minirocket:
// OUT holds the run's dataset, evaluation.txt/.json, report.html and model.rsm.
fs::path record_analysed_run(const fs::path& dir) {
    const auto script = dir / "mr.lua";
    std::ofstream(script) << R"(
local rs = require "rollsense"
local etroll = require "etroll"
rs.on_cleanup(etroll.park)
for _, object in ipairs{ "C1", "P1", "H2" } do
  for r = 1, 6 do etroll.run_trial{ object = object, speed = 10, repetition = r } end
end
rs.analyse{ classifier = "minirocket", params = { num_features = 168 }, folds = 2, repeats = 1 }
)";
    const auto out = dir / "run";
    const auto run = run_rollsense("run " + script.string() + " --profile sim --seed 4 --out " + out.string() + " -q");
    INFO(run.output);
    REQUIRE(run.status == 0);
    REQUIRE(fs::exists(out / "model.rsm"));
    return out;
}

}  // namespace

TEST_CASE("train, report and one repetition on a run analysed with minirocket", "[learn][cli][series][train_report]") {
    rollsense::testing::TempDir dir("rollsense-train-report");
    const auto run = record_analysed_run(dir.path());

    // D: the run's one repetition has no spread, and its JSON says so.
    const auto run_json = JsonReader::parse(file_text(run / "evaluation.json"));
    CHECK(run_json["classifiers"][std::size_t{0}]["accuracy"]["sd"].is_null());
    CHECK_THAT(file_text(run / "evaluation.txt"), Catch::Contains("(one repetition: no spread)") &&
                                                      !Catch::Contains("± 0.0"));

    // A: train prepares the series and fits the model rs.analyse fitted, byte for byte.
    const auto model = dir.path() / "mr.rsm";
    auto r = run_rollsense("train " + run.string() + " --classifier minirocket --set num_features=168 -o " +
                           model.string());
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("trained 'minirocket' on 3 classes"));
    CHECK(file_text(model) == file_text(run / "model.rsm"));
    // ... and predict takes it.
    r = run_rollsense("predict " + model.string() + " " + run.string() + " --classifier minirocket");
    INFO(r.output);
    CHECK(r.status == 0);
    // Tuning a series classifier's deployed model is refused before any work.
    r = run_rollsense("train " + run.string() + " --classifier minirocket --optimize -o " + model.string());
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::Contains("feature classifiers only") && !Catch::Contains("clean "));
    // So is evaluating it with --optimize beside one that can be tuned (user review: the bagged trees' tuning ran
    // 98 s first, then the run failed with exit 1, the classifier named twice).
    r = run_rollsense("evaluate " + run.string() + " --classifier bagged_trees,minirocket --optimize --repeats 1");
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::Contains("classifier 'minirocket' declares no hyperparameters to tune") &&
                             !Catch::Contains("'minirocket': classifier 'minirocket'") && !Catch::Contains("clean "));

    // C: the run's evaluation is not replaced without --force; nothing is lost.
    const std::string before_txt = file_text(run / "evaluation.txt");
    const std::string before_json = file_text(run / "evaluation.json");
    const std::string before_html = file_text(run / "report.html");
    r = run_rollsense("report " + run.string() + " --repeats 2");
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::Contains("already holds report.html, evaluation.txt, evaluation.json") &&
                             Catch::Contains("--force") && Catch::Contains("report-NAME.html"));
    CHECK(file_text(run / "evaluation.txt") == before_txt);
    CHECK(file_text(run / "evaluation.json") == before_json);
    CHECK(file_text(run / "report.html") == before_html);

    // Beside it under another name, with the run's seed by default: the same
    // settings give the run's own figures.
    r = run_rollsense("report " + run.string() + " -o " + (run / "report-again.html").string() +
                      " --classifier minirocket --set num_features=168 --folds 2 --repeats 1");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(fs::exists(run / "report-again.html"));
    const auto again = JsonReader::parse(file_text(run / "evaluation-again.json"));
    CHECK(again["folds"]["seeds"][std::size_t{0}].num() == 4);
    CHECK(again["classifiers"][std::size_t{0}]["accuracy"]["mean"].num() ==
          run_json["classifiers"][std::size_t{0}]["accuracy"]["mean"].num());
    CHECK(file_text(run / "evaluation.txt") == before_txt);
    CHECK(file_text(run / "report.html") == before_html);
    // Another page name gets its own evaluation files too.
    r = run_rollsense("report " + run.string() + " -o " + (dir.path() / "fig.html").string() +
                      " --folds 2 --repeats 2 --set learners=5 --seed 7");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(JsonReader::parse(file_text(dir.path() / "fig-evaluation.json"))["folds"]["seeds"][std::size_t{0}].num() ==
          7);
    // Newcomer review: the clean count was printed as a line, then again in the summary.
    const auto clean = r.output.find("clean ");
    REQUIRE(clean != std::string::npos);
    CHECK(r.output.find(r.output.substr(clean, r.output.find('\n', clean) - clean), clean + 1) == std::string::npos);

    // --force replaces them.
    r = run_rollsense("report " + run.string() + " --force --folds 2 --repeats 2 --set learners=5");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK(file_text(run / "evaluation.json") != before_json);
    CHECK(JsonReader::parse(file_text(run / "evaluation.json"))["folds"]["repeats"].num() == 2);
}

TEST_CASE("a features CSV where the recorded trials are needed is refused first and named (exit 2)", "[learn][cli][csv_input]") {
    const auto dir = rollsense::testing::make_dataset();
    const auto csv = dir / "f.csv";
    auto r = run_rollsense("features " + (dir / "dataset").string() + " -o " + csv.string());
    REQUIRE(r.status == 0);
    for (const std::string& command :
         {"evaluate " + csv.string() + " --prefixes --set learners=3",
          "evaluate " + csv.string() + " --classifier minirocket",
          "evaluate " + csv.string() + " --classifier bagged_trees,minirocket",
          "train " + csv.string() + " --classifier minirocket -o " + (dir / "m.rsm").string()}) {
        INFO(command);
        r = run_rollsense(command);
        INFO(r.output);
        CHECK(r.status == 2);
        CHECK_THAT(r.output, Catch::Contains("'" + csv.string() + "' is not a dataset folder") &&
                                 Catch::Contains("pass the dataset folder"));
        CHECK_THAT(r.output, !Catch::Contains("''"));
        // Before any work: the rows were not even read (no rejection summary, no CV).
        CHECK_THAT(r.output, !Catch::Contains("clean 33 of 36") && !Catch::Contains("accuracy"));
    }
    CHECK_FALSE(fs::exists(dir / "m.rsm"));
    fs::remove_all(dir);
}
