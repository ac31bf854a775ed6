// One catalogue for everything: a user adds a 10th object by adding a row, and
// that object reaches the simulation (it rolls it) and the analyses (the paper
// comparison and the report know its shape), all through the data layer's
// reader.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "analysis/learn/paper_analysis.hpp"
#include "analysis/report/object_order.hpp"
#include "roll_driver.hpp"
#include "rollsense/object_catalogue.hpp"
#include "sim_schema.hpp"
#include "sim_sensor.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::testing::read_file;
using rollsense::testing::TempDir;
using rollsense::testing::write_file;
namespace fs = std::filesystem;

namespace {

// A share folder whose catalogue is the stock one plus a triangular prism.
fs::path share_with_tenth_object(const TempDir& dir) {
    const fs::path stock = fs::path(ROLLSENSE_SHARE_DIR) / kStockCatalogue;
    const fs::path file = dir.path() / "share" / kStockCatalogue;
    write_file(file, read_file(stock) + "T1,triangle,3,20,,0.2,0.4,triangular prism 20 mm edge\n");
    fs::create_directories(dir.path() / "share" / "profiles");  // what marks a share folder
    return dir.path() / "share";
}

}  // namespace

TEST_CASE("a 10th object added as a row reaches the sim", "[sim][catalogue]") {
    const TempDir dir("rollsense-catalogue-reach");
    const fs::path share = share_with_tenth_object(dir);

    auto params = validate_params(sim::sim_schema(), {}, "test");
    REQUIRE(params.ok());
    PluginContext ctx;
    ctx.instance = "tactile";
    ctx.share_dir = share;  // the default 'catalogue' is relative to it
    sim::SimSensor sensor;
    REQUIRE(sensor.on_configure(params.value(), ctx).ok());
    REQUIRE(sensor.catalogue()->objects().size() == 10);

    sim::bench::Recording rec;
    const TrialInfo trial{"T1-test", "T1", "10", 1, 7, {}};
    const auto st = sim::bench::record_roll(sensor, trial, sim::bench::RollPlan{}, rec);
    INFO(st.message());
    REQUIRE(st.ok());
    // It rolled across the array: every barometer felt it (as test_sensor's full roll).
    for (const auto& ch : rec.channels) {
        REQUIRE_FALSE(ch.empty());
        CHECK(*std::max_element(ch.begin(), ch.end()) > 0.01);
    }
}

TEST_CASE("a 10th object added as a row reaches the analyses", "[sim][catalogue]") {
    const TempDir dir("rollsense-catalogue-reach");
    const fs::path share = share_with_tenth_object(dir);
    auto cat = ObjectCatalogue::load(share / kStockCatalogue);
    REQUIRE(cat.ok());

    const auto shapes = learn::object_shapes(cat.value());
    REQUIRE(shapes.size() == 10);
    CHECK(shapes.back().id == "T1");
    CHECK(shapes.back().base == "triangle");
    CHECK(shapes.back().side_mm == 20.0);
    CHECK(shapes.front().cylinder());

    // The paper comparison counts it as a polygon, not as an unknown object.
    std::vector<features::FeatureRow> rows(2);
    rows[0].object = "T1";
    rows[0].clean = true;
    rows[1].object = "C1";
    rows[1].clean = true;
    const std::vector<std::string> classes{"C1", "T1"};
    const std::vector<std::size_t> index{0, 1};
    const std::vector<int> truth{1, 0}, predicted{1, 0};
    const auto a = learn::analyse_like_paper(rows, index, truth, predicted, classes, shapes);
    CHECK(a.unknown_objects.empty());
    CHECK(a.polygons_clean.n == 1);
    CHECK(a.cylinders_clean.n == 1);

    // The report groups it with the polygons of its edge length.
    const auto order = report::order_objects(classes, shapes);
    REQUIRE(order.groups.size() == 2);
    CHECK(order.groups[1].label == "polygons (20 mm)");

    // And the stock list the analyses use by default is read from the share
    // folder's file (CTest runs each test case in its own process, so this is
    // the first read of it here).
    REQUIRE(::setenv("ROLLSENSE_SHARE", share.c_str(), 1) == 0);
    const auto& stock = learn::paper_objects();
    ::unsetenv("ROLLSENSE_SHARE");
    REQUIRE(stock.size() == 10);
    CHECK(stock.back().id == "T1");
}
