#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "toy_data.hpp"

#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::bagged_trees;
namespace fs = std::filesystem;

namespace {

fs::path temp_file(const std::string& name) {
    static const rollsense::testing::TempDir dir("rollsense-test-bt");  // removed when the test process ends
    return dir / name;
}

std::string read(const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void write(const fs::path& f, const std::string& text) {
    std::ofstream out(f, std::ios::binary | std::ios::trunc);
    out << text;
}

}  // namespace

TEST_CASE("save and load give a model with identical predictions", "[bagged_trees][model]") {
    const auto train = toy::overlapping(300, 11);
    EnsembleOptions o;
    o.tree.predictors_per_split = 1;
    o.tree.criterion = SplitCriterion::deviance;
    o.seed = 77;
    BaggedTrees a(o);
    REQUIRE(a.train(train).ok());
    const auto file = temp_file("model.rsm");
    REQUIRE(a.save(file).ok());
    BaggedTrees b;
    REQUIRE(b.load(file).ok());
    CHECK(b.class_names() == a.class_names());
    CHECK(b.options().seed == 77);
    CHECK(b.options().tree.criterion == SplitCriterion::deviance);
    const auto test = toy::overlapping(500, 12);
    for (std::size_t r = 0; r < test.rows; ++r) {
        auto pa = a.predict(test.row(r));
        auto pb = b.predict(test.row(r));
        REQUIRE(pa->label == pb->label);
        REQUIRE(pa->scores == pb->scores);  // bit-identical
    }
    CHECK(b.model().serialize() == read(file));  // save(load(file)) == file
}

TEST_CASE("a damaged model file gives a clear error naming the file", "[bagged_trees][model]") {
    BaggedTrees a;
    REQUIRE(a.train(toy::separable(100, 13)).ok());
    const auto file = temp_file("damaged.rsm");
    REQUIRE(a.save(file).ok());
    const std::string good = read(file);
    BaggedTrees b;

    SECTION("truncated") {
        write(file, good.substr(0, good.size() / 2));
        auto s = b.load(file);
        REQUIRE_FALSE(s.ok());
        CHECK_THAT(s.message(), Catch::Contains(file.string()) && Catch::Contains("truncated"));
    }
    SECTION("truncated inside the checksum line") {
        write(file, good.substr(0, good.size() - 3));
        CHECK_THAT(b.load(file).message(), Catch::Contains("truncated"));
    }
    SECTION("a changed digit") {
        std::string bad = good;
        const auto pos = bad.find("\n0 0.") + 4;  // a threshold of the first split on feature 0
        REQUIRE(pos > 10);
        bad[pos] = bad[pos] == '7' ? '8' : '7';
        write(file, bad);
        auto s = b.load(file);
        REQUIRE_FALSE(s.ok());
        CHECK_THAT(s.message(), Catch::Contains(file.string()) && Catch::Contains("corrupt"));
    }
    SECTION("structure damage is caught before the checksum") {
        std::string bad = good;
        const auto pos = bad.find("tree 0 ");
        bad.replace(pos, 7, "tree 5 ");
        write(file, bad);
        CHECK_THAT(b.load(file).message(), Catch::Contains("line") && Catch::Contains("tree 5"));
    }
    SECTION("not a model at all") {
        write(file, "trial_id,object\n");
        CHECK_THAT(b.load(file).message(), Catch::Contains("is not a rollsense bagged-trees model"));
    }
    SECTION("a newer format version") {
        std::string bad = good;
        bad.replace(0, bad.find('\n'), "rollsense-bagged-trees 9");
        write(file, bad);
        CHECK_THAT(b.load(file).message(), Catch::Contains("version 9"));
    }
    SECTION("missing file") {
        auto s = b.load(file.string() + ".missing");
        CHECK(s.code() == ErrorCode::not_found);
        CHECK_THAT(s.message(), Catch::Contains("rollsense train"));
    }
    // The failed load left the classifier untrained, not half-loaded.
    CHECK(b.class_names().empty());
}
