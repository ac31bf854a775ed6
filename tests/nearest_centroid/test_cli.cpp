// nearest_centroid through the program: listed, evaluated (tuned too) and
// trained by name, as any classifier plugin; and the default classifier read
// from share/analysis/defaults.csv.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "rollsense/features.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace rollsense;
using rollsense::testing::run_rollsense;

namespace {

// Three objects, 12 clean trials each, told apart by the first two features.
fs::path write_features(const rollsense::testing::TempDir& dir) {
    std::vector<features::FeatureRow> rows;
    const char* objects[] = {"C1", "P1", "S2"};
    for (int o = 0; o < 3; ++o)
        for (int r = 0; r < 12; ++r) {
            features::FeatureRow row;
            row.trial_id = std::string(objects[o]) + "-r" + std::to_string(r);
            row.object = objects[o];
            row.speed = "10";
            row.repetition = r;
            row.clean = true;
            for (std::size_t k = 0; k < row.values.size(); ++k)
                row.values[k] = (k < 2 ? 3.0 * o : 0.0) + 0.1 * ((r * 7 + static_cast<int>(k) * 3) % 11);
            rows.push_back(row);
        }
    const auto file = dir / "features.csv";
    REQUIRE(features::write_features_csv(file, rows).ok());
    return file;
}

}  // namespace

TEST_CASE("rollsense plugins lists nearest_centroid", "[nearest_centroid][cli]") {
    auto r = run_rollsense("plugins --params");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("nearest_centroid") && Catch::Contains("shrink"));
}

TEST_CASE("evaluate --optimize and train with --classifier nearest_centroid", "[nearest_centroid][cli]") {
    rollsense::testing::TempDir dir("nearest-centroid-cli");
    const auto features = write_features(dir);
    auto r = run_rollsense("evaluate " + features.string() +
                           " --classifier nearest_centroid --repeats 2 --folds 3 --optimize --evaluations 5");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("accuracy 100.0 %") && Catch::Contains("chosen: shrink=") &&
                             Catch::Contains("nested CV"));

    const auto model = dir / "model.rnc";
    r = run_rollsense("train " + features.string() + " --classifier nearest_centroid --optimize --evaluations 4 -o " +
                      model.string());
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("optimiser 4: error") && Catch::Contains("shrink=") &&
                             Catch::Contains("trained 'nearest_centroid' on 3 classes"));
    std::ifstream in(model);
    std::string first;
    std::getline(in, first);
    CHECK(first == "rollsense-nearest-centroid 1");
}

TEST_CASE("the default classifier comes from share/analysis/defaults.csv", "[nearest_centroid][cli]") {
    rollsense::testing::TempDir dir("nearest-centroid-defaults");
    const auto features = write_features(dir);
    // A share folder whose default is nearest_centroid; everything else copied.
    const auto share = dir / "share";
    fs::copy(ROLLSENSE_SHARE_DIR, share, fs::copy_options::recursive);
    rollsense::testing::write_file(share / "analysis/defaults.csv", "key,value\nclassifier,nearest_centroid\n");
    const std::string env = "ROLLSENSE_SHARE=" + share.string() + " ";

    auto r = rollsense::testing::run_command(env + ROLLSENSE_BIN_DIR "/rollsense train --help");
    CHECK_THAT(r.output, Catch::Contains("classifier plugin (nearest_centroid)"));
    r = rollsense::testing::run_command(env + ROLLSENSE_BIN_DIR "/rollsense evaluate --help");
    CHECK_THAT(r.output, Catch::Contains("classifier plugin (default nearest_centroid)"));
    r = rollsense::testing::run_command(env + ROLLSENSE_BIN_DIR "/rollsense train " + features.string() + " -o " +
                                        (dir / "m").string());
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("trained 'nearest_centroid'"));

    // No defaults file: a clear error, unless the classifier is named.
    fs::remove(share / "analysis/defaults.csv");
    r = rollsense::testing::run_command(env + ROLLSENSE_BIN_DIR "/rollsense train " + features.string() + " -o " +
                                        (dir / "m").string());
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("defaults.csv") && Catch::Contains("--classifier"));
    r = rollsense::testing::run_command(env + ROLLSENSE_BIN_DIR "/rollsense train " + features.string() +
                                        " --classifier nearest_centroid -o " + (dir / "m").string());
    CHECK(r.status == 0);
    r = rollsense::testing::run_command(env + ROLLSENSE_BIN_DIR "/rollsense train --help");
    CHECK_THAT(r.output, Catch::Contains("classifier plugin (none: "));
}
