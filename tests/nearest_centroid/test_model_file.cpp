// The nearest-centroid model file: exact round trip, and every kind of bad
// file refused with the file, the line and the way out.
#include <catch2/catch.hpp>

#include "rollsense/nearest_centroid/nearest_centroid.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::nearest_centroid::Model;
using rollsense::nearest_centroid::NearestCentroid;

namespace {

std::string trained_text() {
    FeatureTable t;
    t.feature_names = {"peak width", "f2"};
    t.class_names = {"C1", "S 2"};
    t.x = {0.1, 1.0 / 3.0, 0.2, 2.0, 5.0, 1e-9, 7.0, 3.5};
    t.y = {0, 0, 1, 1};
    t.rows = 4;
    NearestCentroid c;
    REQUIRE(c.train(t).ok());
    return c.model().serialize();
}

Status parse(const std::string& text) {
    Model m;
    return m.deserialize(text, "m.rsm");
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("a nearest-centroid model reads back exactly", "[nearest_centroid][model_file]") {
    const std::string text = trained_text();
    CHECK(text.rfind("rollsense-nearest-centroid 1\n", 0) == 0);
    Model m;
    REQUIRE(m.deserialize(text, "m.rsm").ok());
    CHECK(m.class_names == std::vector<std::string>{"C1", "S 2"});
    CHECK(m.feature_names == std::vector<std::string>{"peak width", "f2"});
    CHECK(m.serialize() == text);
}

TEST_CASE("bad nearest-centroid model files are refused with the line and the remedy",
          "[nearest_centroid][model_file]") {
    const std::string text = trained_text();
    CHECK_THAT(parse("rollsense-bagged-trees 1\nclasses 1\n").message(),
               Catch::Contains("not a nearest_centroid model") && Catch::Contains("another classifier"));
    CHECK_THAT(parse("").message(), Catch::Contains("is empty"));
    CHECK_THAT(parse(replace(text, "rollsense-nearest-centroid 1", "rollsense-nearest-centroid 2")).message(),
               Catch::Contains("line 1") && Catch::Contains("version 2") && Catch::Contains("reads version 1"));
    CHECK_THAT(parse(text.substr(0, text.size() - 5)).message(), Catch::Contains("truncated"));
    CHECK_THAT(parse(text.substr(0, text.find("\ncentroid 1") + 1)).message(), Catch::Contains("truncated"));
    CHECK_THAT(parse(replace(text, "classes 2", "classes 3")).message(), Catch::Contains("line"));
    CHECK_THAT(parse(replace(text, "centroid 1 ", "centroid 0 ")).message(),
               Catch::Contains("line 10") && Catch::Contains("where centroid 1 belongs"));
    CHECK_THAT(parse(replace(text, "class 2 C1", "class 2 C9")).message(), Catch::Contains("corrupt"));
    CHECK_THAT(parse(replace(text, "class 2 C1", "class 0 C1")).message(), Catch::Contains("corrupt"));
    CHECK_THAT(parse(text + "more\n").message(), Catch::Contains("after the checksum"));
    CHECK_THAT(parse(replace(text, "shrink=0", "shrink=-1")).message(), Catch::Contains("out of range"));
}

TEST_CASE("nearest_centroid saves and loads through files", "[nearest_centroid][model_file]") {
    rollsense::testing::TempDir dir("nearest-centroid-model");
    NearestCentroid c;
    CHECK_THAT(c.save(dir / "m.rsm").message(), Catch::Contains("not trained"));
    CHECK_THAT(c.load(dir / "missing.rsm").message(), Catch::Contains("cannot be opened"));
    Model m;
    REQUIRE(m.deserialize(trained_text(), "x").ok());
    std::ofstream(dir / "m.rsm") << m.serialize();
    REQUIRE(c.load(dir / "m.rsm").ok());
    CHECK(c.class_names() == m.class_names);
}
