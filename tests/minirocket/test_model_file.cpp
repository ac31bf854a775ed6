// Save/load: a reloaded model predicts exactly as the saved one; foreign,
// newer, cut and damaged files are refused with a reason.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "rollsense/minirocket/minirocket.hpp"
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

MiniRocket trained() {
    Options o;
    o.transform.num_features = 1000;
    o.transform.seed = 5;
    MiniRocket m(o);
    REQUIRE(m.train(shapes::make(12, 40, 4)).ok());
    return m;
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
    const auto test = shapes::make(5, 40, 99);
    for (std::size_t i = 0; i < test.rows; ++i) CHECK(back.predict(test.row(i))->scores == m.predict(test.row(i))->scores);
    // Saving the reloaded model gives the same bytes.
    REQUIRE(back.save(dir.path() / "again.rsm").ok());
    CHECK(slurp(dir.path() / "again.rsm") == slurp(file));
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
    refused("rollsense-minirocket 2\n" + good.substr(good.find('\n') + 1), "newer than this build");
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
