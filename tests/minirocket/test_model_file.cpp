// Save/load: a reloaded model predicts exactly as the saved one and gives back
// the series rule it was trained with; a version 1 file (no series_rule line)
// still loads; foreign, newer, cut and damaged files are refused with a reason.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "rollsense/minirocket/minirocket.hpp"
#include "rollsense/model_text.hpp"
#include "shapes.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::minirocket;

namespace {
std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}
void spit(const std::filesystem::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

// Opaque to the plugin: any one line (the analysis layer writes and reads it).
const std::string kRule = "length=40 amplitude=z_per_channel";

MiniRocket trained(const std::string& rule = kRule) {
    Options o;
    o.transform.num_features = 1000;
    o.transform.seed = 5;
    MiniRocket m(o);
    auto table = shapes::make(12, 40, 4);
    table.series_rule = rule;
    REQUIRE(m.train(table).ok());
    return m;
}

// `text` with its first line replaced by `first` and its series_rule line
// removed (or replaced by `rule_line`), the checksum made good again.
std::string rewritten(const std::string& text, const std::string& first, const std::string& rule_line = "") {
    std::string body = text.substr(0, text.rfind("checksum "));
    body = first + "\n" + body.substr(body.find('\n') + 1);
    const auto at = body.find("series_rule");
    body.replace(at, body.find('\n', at) + 1 - at, rule_line.empty() ? "" : rule_line + "\n");
    model_text::put_checksum(body);
    return body;
}
}  // namespace

TEST_CASE("a saved and reloaded model predicts exactly the same", "[minirocket][model_file]") {
    rollsense::testing::TempDir dir;
    const auto file = dir.path() / "m.rsm";
    const MiniRocket m = trained();
    REQUIRE(m.save(file).ok());
    MiniRocket back;
    REQUIRE(back.load(file).ok());
    CHECK(back.class_names() == m.class_names());
    CHECK(back.options().transform.seed == 5);
    CHECK(back.options().transform.num_features == 1000);
    CHECK(back.model().alpha == m.model().alpha);
    CHECK(back.series_rule() == kRule);
    CHECK_THAT(slurp(file), Catch::StartsWith("rollsense-minirocket 2\n") && Catch::Contains("\nseries_rule " + kRule + "\n"));
    const auto test = shapes::make(5, 40, 99);
    for (std::size_t i = 0; i < test.rows; ++i) CHECK(back.predict(test.row(i))->scores == m.predict(test.row(i))->scores);
    // Saving the reloaded model gives the same bytes.
    REQUIRE(back.save(dir.path() / "again.rsm").ok());
    CHECK(slurp(dir.path() / "again.rsm") == slurp(file));
}

TEST_CASE("a model trained without a series rule keeps an empty one", "[minirocket][model_file]") {
    rollsense::testing::TempDir dir;
    const MiniRocket m = trained("");
    REQUIRE(m.save(dir.path() / "m.rsm").ok());
    CHECK_THAT(slurp(dir.path() / "m.rsm"), Catch::Contains("\nseries_length 40\nseries_rule\noptions "));
    MiniRocket back;
    REQUIRE(back.load(dir.path() / "m.rsm").ok());
    CHECK(back.series_rule().empty());
    // A rule is one line of the file: a line break in it is refused, not written.
    const MiniRocket broken = trained("amplitude=z_per_channel\nalpha 3");
    auto s = broken.save(dir.path() / "broken.rsm");
    REQUIRE(!s.ok());
    CHECK_THAT(s.error().message, Catch::Contains("line break"));
    CHECK(!std::filesystem::exists(dir.path() / "broken.rsm"));
}

TEST_CASE("a version 1 model file (before the series rule) still loads, with no rule", "[minirocket][model_file]") {
    rollsense::testing::TempDir dir;
    const MiniRocket m = trained();
    REQUIRE(m.save(dir.path() / "m.rsm").ok());
    spit(dir.path() / "v1.rsm", rewritten(slurp(dir.path() / "m.rsm"), "rollsense-minirocket 1"));
    MiniRocket old;
    const auto s = old.load(dir.path() / "v1.rsm");
    INFO((s.ok() ? std::string() : s.error().message));
    REQUIRE(s.ok());
    CHECK(old.series_rule().empty());
    const auto test = shapes::make(3, 40, 7);
    for (std::size_t i = 0; i < test.rows; ++i) CHECK(old.predict(test.row(i))->scores == m.predict(test.row(i))->scores);
}

TEST_CASE("foreign, newer, cut and damaged model files are refused", "[minirocket][model_file][errors]") {
    rollsense::testing::TempDir dir;
    const auto file = dir.path() / "m.rsm";
    const MiniRocket m = trained();
    REQUIRE(m.save(file).ok());
    const std::string good = slurp(file);
    MiniRocket target;

    auto refused = [&](const std::string& text, const std::string& reason) {
        spit(dir.path() / "bad.rsm", text);
        auto s = target.load(dir.path() / "bad.rsm");
        REQUIRE(!s.ok());
        INFO(s.error().message);
        CHECK(s.error().message.find(reason) != std::string::npos);
        CHECK(!target.model().trained());  // a failed load leaves the classifier as it was
    };
    refused("rollsense-bagged-trees 1\nclasses 2\n", "not a rollsense MiniRocket model");
    refused("rollsense-minirocket 3\n" + good.substr(good.find('\n') + 1), "newer than this build");
    refused(rewritten(good, "rollsense-minirocket 2"), "expected the 'series_rule' line");
    refused(rewritten(good, "rollsense-minirocket 1", "series_rule " + kRule), "expected the 'options' line");
    refused(good.substr(0, good.size() / 2), "truncated");
    std::string damaged = good;
    damaged[damaged.find("intercept ") + 11] ^= 1;
    refused(damaged, "checksum");
    std::string huge = good;
    huge.replace(huge.find("classes 3"), 9, "classes 99999999999");
    refused(huge, "implausible classes");
    std::string other_layout = good;
    other_layout.replace(other_layout.find("series_length 40"), 16, "series_length 64");
    refused(other_layout, "combinations where the options and series length give");

    auto missing = target.load(dir.path() / "nope.rsm");
    REQUIRE(!missing.ok());
    CHECK(missing.error().code == ErrorCode::not_found);
    MiniRocket untrained;
    CHECK(!untrained.save(dir.path() / "x.rsm").ok());
}
