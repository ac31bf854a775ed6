// share/analysis/defaults.csv: the one home of the default classifier.
#include <catch2/catch.hpp>

#include "analysis/learn/defaults.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::learn;

namespace {

std::filesystem::path share_with(const testing::TempDir& dir, const std::string& csv) {
    std::filesystem::create_directories(dir / "analysis");
    testing::write_file(dir / "analysis/defaults.csv", csv);
    return dir.path();
}

}  // namespace

TEST_CASE("the shipped defaults name a classifier", "[learn][defaults]") {
    auto d = default_classifier(ROLLSENSE_SHARE_DIR);
    REQUIRE(d.ok());
    CHECK_FALSE(d->empty());
    auto given = classifier_or_default("other", ROLLSENSE_SHARE_DIR);
    REQUIRE(given.ok());
    CHECK(*given == "other");
    CHECK(with_default_classifier("x ({default_classifier}) {default_classifier}", ROLLSENSE_SHARE_DIR) ==
          "x (" + *d + ") " + *d);
}

TEST_CASE("defaults.csv: comments, spaces, and errors naming file and line", "[learn][defaults]") {
    testing::TempDir dir("defaults");
    auto share = share_with(dir, "# comment\n\nkey,value\n other , x \nclassifier, my_plugin\n");
    CHECK(*default_classifier(share) == "my_plugin");
    CHECK(*analysis_default(share, "other") == "x");
    CHECK_THAT(analysis_default(share, "missing").error().message,
               Catch::Contains("no 'missing' row") && Catch::Contains("defaults.csv"));

    share = share_with(dir, "key,value\nclassifier\n");
    CHECK_THAT(default_classifier(share).error().message, Catch::Contains("defaults.csv:2") &&
                                                              Catch::Contains("expected 'key,value'"));
    share = share_with(dir, "classifier,x\n");
    CHECK_THAT(default_classifier(share).error().message, Catch::Contains("defaults.csv:1") &&
                                                              Catch::Contains("header"));
    share = share_with(dir, "key,value\nclassifier,\n");
    CHECK_THAT(default_classifier(share).error().message, Catch::Contains("empty value"));

    const auto nowhere = dir / "no-share";
    CHECK_THAT(default_classifier(nowhere).error().message, Catch::Contains("cannot be opened") &&
                                                                Catch::Contains("ROLLSENSE_SHARE"));
    CHECK(classifier_or_default("given", nowhere).ok());  // an explicit name needs no file
    CHECK_THAT(with_default_classifier("({default_classifier})", nowhere), Catch::StartsWith("(none: "));
}
