// The object catalogue: the paper's Table II loads; malformed rows give errors
// naming the file, the line and the column.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "rollsense/object_catalogue.hpp"

using namespace rollsense;

namespace {
std::filesystem::path write_temp(const std::string& name, const std::string& text) {
    const auto dir = std::filesystem::temp_directory_path() / "rollsense_test_sim";
    std::filesystem::create_directories(dir);
    const auto file = dir / name;
    std::ofstream(file) << text;
    return file;
}
const std::string kHeader = "id,base,sides,side_mm,diameter_mm,edge_radius_min_mm,edge_radius_max_mm,description\n";
}  // namespace

TEST_CASE("the stock catalogue holds the nine objects of the paper's Table II", "[sim][catalogue]") {
    auto cat = ObjectCatalogue::load(std::filesystem::path(ROLLSENSE_SHARE_DIR) / "objects" / "paper_table2.csv");
    INFO((cat.ok() ? std::string() : cat.error().describe()));
    REQUIRE(cat.ok());
    REQUIRE(cat->objects().size() == 9);
    CHECK(cat->find("C2")->is_cylinder());
    CHECK(cat->find("C2")->diameter == 27.0);
    const auto* p2 = cat->find("P2");
    REQUIRE(p2);
    CHECK(p2->sides == 5);
    CHECK(p2->side == 18.0);
    CHECK(p2->flat_width() == Approx(24.8 / 2 + 30.6 / 2).margin(0.1));  // inradius + circumradius
    CHECK(cat->find("H1")->flat_width() == Approx(22.5).margin(0.05));   // inscribed diameter
    CHECK(cat->find("S2")->flat_width() == Approx(18.0).margin(1e-9));
    CHECK(cat->find("X9") == nullptr);
}

TEST_CASE("a malformed catalogue entry is an error naming file, line and column", "[sim][catalogue]") {
    struct Case {
        std::string row;
        std::string column;
        std::string says;
    };
    const Case cases[] = {
        {"S1,square,4,thirteen,18.4,0.3,1.5,x\n", "side_mm", ""},
        {"S1,sqaure,4,13,18.4,0.3,1.5,x\n", "base", "unknown base 'sqaure'"},
        {"S1,square,5,13,18.4,0.3,1.5,x\n", "sides", "contradicts base"},
        {"S1,square,4,13,25.5,0.3,1.5,x\n", "diameter_mm", "expected 18.38"},
        {"C9,circle,0,,,,,x\n", "diameter_mm", "diameter_mm > 0"},
        {"S1,square,4,13,18.4,1.5,0.3,x\n", "edge_radius_max_mm", "min <= max"},
        {"S1,square,4,13,18.4,0.3,9,x\n", "edge_radius_max_mm", "too large"},
        {",square,4,13,18.4,0.3,1.5,x\n", "id", "needs an id"},
    };
    for (const auto& c : cases) {
        const auto file = write_temp("bad.csv", kHeader + "C1,circle,0,,18,,,ok\n" + c.row);
        auto cat = ObjectCatalogue::load(file);
        REQUIRE_FALSE(cat.ok());
        const std::string msg = cat.error().message;
        INFO(msg);
        CHECK(msg.find(file.string()) != std::string::npos);
        CHECK(msg.find(":3") != std::string::npos);  // the offending line
        CHECK(msg.find(c.column) != std::string::npos);
        if (!c.says.empty()) CHECK(msg.find(c.says) != std::string::npos);
    }
}

TEST_CASE("catalogue structure errors are explained", "[sim][catalogue]") {
    auto missing = ObjectCatalogue::load("/nonexistent/objects.csv");
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().message.find("/nonexistent/objects.csv") != std::string::npos);
    CHECK(missing.error().message.find("catalogue") != std::string::npos);

    auto no_column = ObjectCatalogue::load(write_temp("nocol.csv", "id,base\nC1,circle\n"));
    REQUIRE_FALSE(no_column.ok());
    CHECK(no_column.error().message.find("sides") != std::string::npos);

    auto dup = ObjectCatalogue::load(write_temp("dup.csv", kHeader + "C1,circle,0,,18,,,a\nC1,circle,0,,20,,,b\n"));
    REQUIRE_FALSE(dup.ok());
    CHECK(dup.error().message.find("appears twice") != std::string::npos);

    auto empty = ObjectCatalogue::load(write_temp("empty.csv", kHeader));
    REQUIRE_FALSE(empty.ok());
    CHECK(empty.error().message.find("no objects") != std::string::npos);
}

TEST_CASE("a user-added object loads, diameter derived when left empty", "[sim][catalogue]") {
    auto cat = ObjectCatalogue::load(write_temp("user.csv", kHeader + "T1,triangle,3,20,,0.2,0.4,my prism\n"));
    INFO((cat.ok() ? std::string() : cat.error().describe()));
    REQUIRE(cat.ok());
    CHECK(cat->find("T1")->diameter == Approx(20.0 / std::sin(3.14159265358979323846 / 3)));
}

// Issue 22 item 7: a NaN edge radius overflowed the tumbling model's buffers,
// side_mm=1e41 took 11 s per trial, sides=1e10 was cast to int (undefined).
TEST_CASE("catalogue numbers outside their physical ranges are refused with file:line:column",
          "[sim][catalogue][bounds]") {
    struct Case {
        std::string row;
        std::string column;
        std::string says;
    };
    const Case cases[] = {
        {"S1,square,4,13,18.4,0.3,NaN,x\n", "edge_radius_max_mm", "not a finite number"},
        {"S1,square,4,13,18.4,nan,1.5,x\n", "edge_radius_min_mm", "not a finite number"},
        {"S1,square,4,13,18.4,0.3,inf,x\n", "edge_radius_max_mm", "not a finite number"},
        {"S1,square,4,13,18.4,-inf,1.5,x\n", "edge_radius_min_mm", "not a finite number"},
        {"S1,square,4,1e41,,0.3,1.5,x\n", "side_mm", "<= 200 mm"},
        {"S1,square,4,NaN,,0.3,1.5,x\n", "side_mm", "> 0"},
        {"S1,square,4,inf,,0.3,1.5,x\n", "side_mm", "> 0"},
        {"S1,square,1e10,13,,0.3,1.5,x\n", "sides", "whole number"},
        {"S1,square,NaN,13,,0.3,1.5,x\n", "sides", "whole number"},
        {"S1,square,-4,13,,0.3,1.5,x\n", "sides", "whole number"},
        {"S1,square,4.5,13,,0.3,1.5,x\n", "sides", "whole number"},
        {"S1,square,4,13,NaN,0.3,1.5,x\n", "diameter_mm", "finite"},
        {"C9,circle,0,,1e300,,,x\n", "diameter_mm", "<= 200 mm"},
        {"C9,circle,0,,NaN,,,x\n", "diameter_mm", "> 0"},
        {"C9,circle,0,,18,NaN,,x\n", "edge_radius_min_mm", "finite"},
        {"../x,circle,0,,18,,,x\n", "id", "A-Z a-z 0-9"},
        {"a b,circle,0,,18,,,x\n", "id", "A-Z a-z 0-9"},
        {std::string(41, 'L') + ",circle,0,,18,,,x\n", "id", "1 to 40 characters"},
    };
    for (const auto& c : cases) {
        const auto file = write_temp("bounds.csv", kHeader + "C1,circle,0,,18,,,ok\n" + c.row);
        auto cat = ObjectCatalogue::load(file);
        INFO(c.row);
        REQUIRE_FALSE(cat.ok());
        const std::string msg = cat.error().message;
        INFO(msg);
        CHECK(msg.find(file.string() + ":3: column '" + c.column + "'") != std::string::npos);
        CHECK(msg.find(c.says) != std::string::npos);
    }
}

TEST_CASE("the largest objects the ranges allow still load", "[sim][catalogue][bounds]") {
    const auto file = write_temp("edge.csv", kHeader + "C1,circle,0,,200,,,big\nT1,triangle,3,200,,0,0,big\n" +
                                                 "D1,octagon,8,0.5,,0,0.2,small\n" + std::string(40, 'L') +
                                                 ",circle,0,,1,,,longest id\n");
    auto cat = ObjectCatalogue::load(file);
    INFO((cat.ok() ? std::string() : cat.error().describe()));
    REQUIRE(cat.ok());
    CHECK(cat->objects().size() == 4);
}

TEST_CASE("object_problem checks an object built without the reader", "[sim][catalogue][bounds]") {
    ObjectSpec o;
    o.id = "S1";
    o.base = "square";
    o.sides = 4;
    o.side = 13.0;
    o.diameter = 18.38;
    o.edge_radius_min = 0.3;
    o.edge_radius_max = 1.5;
    CHECK_FALSE(object_problem(o).has_value());
    o.edge_radius_max = std::nan("");
    REQUIRE(object_problem(o).has_value());
    CHECK(object_problem(o)->column == "edge_radius_max_mm");
    o.edge_radius_max = 1.5;
    o.sides = 1000;
    REQUIRE(object_problem(o).has_value());
    CHECK(object_problem(o)->column == "sides");
}
