// The classifier plugin contract, enforced in one place (checked_classifier)
// whatever the command: scores are a distribution over the classes whose
// highest is the predicted label (rollsense/classifier.hpp), and an exception
// thrown from the plugin is a plugin error (exit 3) naming the plugin with the
// exception's text. Through the program, with the test plugin test_odd_scores
// (tests/learn/plugins), whose parameter `mode` chooses what goes wrong.
#include <catch2/catch.hpp>

#include <filesystem>

#include "cli_dataset.hpp"
#include "temp_dir.hpp"
#include "run_command.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kPluginPath = std::string(" --plugin-path ") + ROLLSENSE_LEARN_TEST_PLUGIN_DIR;
const std::string kPlugin = kPluginPath + " --classifier test_odd_scores";
const std::string kNamed = "plugin error: classifier plugin 'test_odd_scores' ";

using rollsense::testing::count_of;
rollsense::testing::CommandRun rollsense_cli(const std::string& args) { return rollsense::testing::run_rollsense(args); }

// evaluate with `mode` must stop with exit 3 saying `says` after the plugin's name, writing nothing.
void check_evaluate_refuses(const fs::path& dir, const std::string& mode, const std::string& says) {
    const auto out = dir / ("eval-mode" + mode + ".txt");
    const auto r = rollsense_cli("evaluate " + (dir / "dataset").string() + " --folds 3 --repeats 1" + kPlugin +
                                 " --set mode=" + mode + " -o " + out.string());
    INFO(r.output);
    CHECK(r.status == 3);
    // evaluate puts the repetition and fold between "plugin error" and the plugin's own message.
    CHECK_THAT(r.output, Catch::Contains("rollsense evaluate: plugin error: ") &&
                             Catch::Contains("classifier plugin 'test_odd_scores' " + says));
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(fs::path(out).replace_extension(".json")));
}

// train with `mode` (the test plugin keeps its mode in the model file, so
// predict's load of it behaves as the mode says); the model's path.
fs::path trained(const fs::path& dir, const std::string& mode) {
    const auto model = dir / ("mode" + mode + ".model");
    const auto r = rollsense_cli("train " + (dir / "dataset").string() + kPlugin + " --set mode=" + mode + " -o " +
                                 model.string());
    INFO(r.output);
    REQUIRE(r.status == 0);
    return model;
}

// `trial`: the trial a prediction broke on, named before the plugin ("" for a model that does not load).
void check_predict_refuses(const fs::path& dir, const fs::path& model, const std::string& says,
                           const std::string& trial = "trial 'C1-r0': ") {
    const auto r = rollsense_cli("predict " + model.string() + " " + (dir / "dataset").string() + kPluginPath);
    INFO(r.output);
    CHECK(r.status == 3);
    const std::string plugin = kNamed.substr(std::string("plugin error: ").size());
    CHECK_THAT(r.output, Catch::Contains("rollsense predict: plugin error: " + trial + plugin + says));
    CHECK_THAT(r.output, !Catch::Contains("unexpected error"));
}

}  // namespace

// Review: a plugin returning scores [0, 7, 0] got "P1 7.000" printed by predict
// (exit 0) and its scores written to evaluation.json.
TEST_CASE("scores that are not a distribution with the label highest stop evaluate and predict, naming the plugin",
          "[learn][cli][plugin]") {
    const auto dir = rollsense::testing::make_dataset();
    const struct {
        const char* mode;
        const char* says;
    } cases[] = {{"5", "returned scores summing to 7; scores are a distribution over the classes, summing to 1"},
                 {"6", "returned a negative score (-0.5) for class '"},
                 {"7", "predicted 'C1' (score 0) but scored 'P1' highest (1); the predicted class is the one with the highest score"}};
    for (const auto& c : cases) {
        INFO("mode " << c.mode);
        check_evaluate_refuses(dir, c.mode, c.says);
        check_predict_refuses(dir, trained(dir, c.mode), c.says);
    }
    fs::remove_all(dir);
}

// Review: predict said "rollsense predict: unexpected error: boom in predict"
// (exit 1); evaluate "classifier threw during prediction" without the plugin's
// name; train "classifier threw during training: boom in train", no name.
TEST_CASE("a classifier plugin that throws is a plugin error naming it with the exception's text in every command",
          "[learn][cli][plugin]") {
    const auto dir = rollsense::testing::make_dataset();
    const std::string d = (dir / "dataset").string();
    check_evaluate_refuses(dir, "8", "threw during prediction: boom in predict");
    check_evaluate_refuses(dir, "9", "threw during training: boom in train");
    check_predict_refuses(dir, trained(dir, "8"), "threw during prediction: boom in predict");

    const auto model = dir / "mode9.model";
    auto r = rollsense_cli("train " + d + kPlugin + " --set mode=9 -o " + model.string());
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Catch::Contains(kNamed + "threw during training: boom in train"));
    CHECK_FALSE(fs::exists(model));

    const auto throws_on_load = trained(dir, "10");
    check_predict_refuses(dir, throws_on_load,
                          "threw during loading " + throws_on_load.string() + ": boom in load", "");
    fs::remove_all(dir);
}

// Review: input(), search_space() and class_names() have no error return; what
// they threw ended evaluate as an "unexpected error" (exit 1), or, from a
// fold's thread, with std::terminate.
TEST_CASE("a classifier plugin that throws where it has no error return is a plugin error naming it",
          "[learn][cli][plugin]") {
    const auto dir = rollsense::testing::make_dataset();
    check_evaluate_refuses(dir, "11", "threw during input: boom in input");
    check_evaluate_refuses(dir, "13", "threw during class_names: boom in class_names");
    const auto r = rollsense_cli("evaluate " + (dir / "dataset").string() + " --folds 3 --repeats 1 --optimize" +
                                 kPlugin + " --set mode=12");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Catch::Contains(kNamed + "threw during search_space: boom in search_space"));
    CHECK_THAT(r.output, !Catch::Contains("unexpected error"));
    fs::remove_all(dir);
}

// Review: a plugin whose class_names() was empty once trained was reported as
// "predicted label 0 outside its 0 classes", as if its predictions were wrong.
TEST_CASE("a classifier plugin with no class names once trained is said to return none, naming it",
          "[learn][cli][plugin]") {
    const auto dir = rollsense::testing::make_dataset();
    const std::string says = "returned no class names after training (class_names() is empty)";
    check_evaluate_refuses(dir, "15", says);
    const auto model = dir / "mode15.model";
    const auto r = rollsense_cli("train " + (dir / "dataset").string() + kPlugin + " --set mode=15 -o " + model.string());
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Catch::Contains(kNamed + says));
    CHECK_THAT(r.output, !Catch::Contains("outside its"));
    CHECK_FALSE(fs::exists(model));
    fs::remove_all(dir);
}

// Review: a search space naming a parameter the schema does not declare passed
// `plugins --check`, and `evaluate --optimize` failed only after the preset's
// cross-validation, when tuning first set the parameter.
TEST_CASE("a classifier plugin whose search space names an undeclared parameter is refused by plugins --check and "
          "before evaluate --optimize cross-validates", "[learn][cli][plugin]") {
    const std::string path = std::string(" --plugin-path ") + ROLLSENSE_TEST_PLUGINS_DIR + "/test-plugins-stray-search";
    const std::string says = "classifier plugin 'test_stray_search' names the parameter 'depth' in its search_space(), "
                             "which its schema() does not declare (it declares: smoothing)";
    const std::string way_out = "declare 'depth' in schema() or drop it from search_space()";
    auto r = rollsense_cli("plugins --check" + path);
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Catch::Contains(says) && Catch::Contains(way_out));
    r = rollsense_cli("plugins" + path);  // listing alone does not configure plugins
    CHECK(r.status == 0);
    CHECK_THAT(r.output, !Catch::Contains(says));

    const auto dir = rollsense::testing::make_dataset();
    const std::string evaluate = "evaluate " + (dir / "dataset").string() + " --folds 3 --repeats 1" + path +
                                 " --classifier test_stray_search -o " + (dir / "eval.txt").string();
    r = rollsense_cli(evaluate + " --optimize");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Catch::Contains(says) && Catch::Contains(way_out));
    CHECK_THAT(r.output, !Catch::Contains("cross-validating the preset"));
    CHECK_FALSE(fs::exists(dir / "eval.txt"));
    // Without --optimize evaluate still asks for the space (it reports it), and refuses it as a search_space that
    // throws is refused.
    r = rollsense_cli(evaluate);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Catch::Contains(says));
    fs::remove_all(dir);
}

// User review (out-of-tree plugins): a search space wider than the schema passed --check and failed at the first
// optimiser evaluation, after the preset's CV, read as the user's own value (exit 1); a plugin that cannot be
// configured with its defaults passed --check, which the docs say configures it.
TEST_CASE("plugins --check refuses a search space wider than the schema, and a classifier its defaults cannot configure",
          "[learn][cli][plugin]") {
    const std::string plugins = std::string(" --plugin-path ") + ROLLSENSE_TEST_PLUGINS_DIR + "/test-plugins-";
    const std::string wide = "classifier plugin 'test_wide_search': search_space(): key 'smoothing': 50 is outside "
                             "the allowed range [0, 10]; tuning may try only values its schema() accepts: the plugin "
                             "must narrow its search_space() or widen its schema()";
    auto r = rollsense_cli("plugins --check" + plugins + "wide-search");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "FAILED: " + wide) == 1);
    const auto dir = rollsense::testing::make_dataset();
    r = rollsense_cli("evaluate " + (dir / "dataset").string() + " --folds 3 --repeats 1 --optimize" + plugins +
                      "wide-search --classifier test_wide_search -o " + (dir / "eval.txt").string());
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, wide) == 1);
    CHECK_THAT(r.output, !Catch::Contains("cross-validating the preset"));
    // Diff review: through rs.analyse the refusal reached Lua as a C++ exception, said "(error object is a table value)".
    const auto script = dir / "tune.lua";
    rollsense::testing::write_file(script, "require('rollsense').analyse{ dataset = '" + (dir / "dataset").string() +
                                               "', folds = 3, repeats = 1, optimize = true, classifier = "
                                               "'test_wide_search' }\n");
    r = rollsense_cli("run " + script.string() + plugins + "wide-search --out " + (dir / "tuned").string());
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "tune.lua:1: " + wide) == 1);
    // A space tuning cannot search at all: a real scale for an integer parameter.
    r = rollsense_cli("plugins --check" + plugins + "crooked-search");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "FAILED: classifier plugin 'test_crooked_search': search_space() gives 'neighbours' "
                             "a real scale for an integer parameter, which tuning cannot search") == 1);
    fs::remove_all(dir);

    r = rollsense_cli("plugins --check" + plugins + "throwing-configure");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "FAILED: configured with its defaults: classifier plugin 'test_throwing_configure': "
                             "threw an exception in configure: no licence file found") == 1);

    // Plugin review: a plugin that refuses its own defaults was the command line's mistake (exit 2) in evaluate.
    const auto data = rollsense::testing::make_dataset();
    r = rollsense_cli("evaluate " + (data / "dataset").string() + " --folds 3 --repeats 1" + plugins +
                      "refusing-configure --classifier test_refusing_configure -o " + (data / "eval.txt").string());
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK(count_of(r.output, "smoothing 1 is not supported (no parameter was given: the plugin refuses its own "
                             "defaults)") == 1);
    // A parameter given that it refuses stays the command line's.
    r = rollsense_cli("evaluate " + (data / "dataset").string() + " --folds 3 --repeats 1" + plugins +
                      "refusing-configure --classifier test_refusing_configure:smoothing=1 -o " +
                      (data / "eval.txt").string());
    INFO(r.output);
    CHECK(r.status == 2);
    fs::remove_all(data);
}
