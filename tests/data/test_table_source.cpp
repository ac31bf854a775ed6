// TableSource: where a Lua file writes its table keys, read from the text; a
// line it cannot be sure of is left out, never guessed.
#include <catch2/catch.hpp>

#include <cmath>

#include "rollsense/table_source.hpp"

using rollsense::ParamValue;
using rollsense::TableSource;

TEST_CASE("keys are found at the line they are written, through nesting, lists and Lua's comments and strings",
          "[table_source]") {
    const TableSource src("p.lua", R"(-- a comment with { braces } and key = 1
--[==[ a long comment
  sample_rate_hz = 99, }
]==]
return {
  description = "a string with { and } and -- in it",
  sample_rate_hz = 31.1,
  devices = {
    hand = include("mock-hand"),
    tactile = { plugin = "sim",
      params = { [[long { string]], ["quoted key"] = 2,
                 width = setting("w", { 1, 2 }) } },
  },
  record_joints = { "a",
                    "b" },
})");
    CHECK(src.where("description", nullptr) == "p.lua:6");
    CHECK(src.where("sample_rate_hz", nullptr) == "p.lua:7");
    CHECK(src.where("devices", nullptr) == "p.lua:8");
    CHECK(src.where("devices.hand", nullptr) == "p.lua:9");
    CHECK(src.where("devices.hand.params.joints", nullptr).empty());  // not written in this file
    CHECK(src.where("devices.tactile.plugin", nullptr) == "p.lua:10");
    CHECK(src.where("devices.tactile.params.1", nullptr) == "p.lua:11");
    CHECK(src.where("devices.tactile.params.quoted key", nullptr) == "p.lua:11");
    CHECK(src.where("devices.tactile.params.width", nullptr) == "p.lua:12");
    CHECK(src.where("record_joints.2", nullptr) == "p.lua:15");
    CHECK(src.where("clock", nullptr).empty());  // not written here: the caller names the profile file
}

TEST_CASE("a value that is not what the file wrote there, or a key written twice, gives no line", "[table_source]") {
    const TableSource src("p.lua", "local base = { rate = 5 }\n"
                                   "return {\n"
                                   "  rate = 5,\n"
                                   "  clock = \"virtual\", on = true, gain = -2,\n"
                                   "  joints = { a = { min = 0x10 } },\n"
                                   "}\n");
    const ParamValue virtual_clock{std::string("virtual")}, other_clock{std::string("monotonic")};
    CHECK(src.where("clock", &virtual_clock) == "p.lua:4");
    CHECK(src.where("clock", &other_clock).empty());  // set later (an assignment, a --set): not this line
    const ParamValue yes{true}, no{false}, minus_two{std::int64_t{-2}}, two{2.0}, sixteen{16.0};
    CHECK(src.where("on", &yes) == "p.lua:4");
    CHECK(src.where("on", &no).empty());
    CHECK(src.where("gain", &minus_two) == "p.lua:4");
    CHECK(src.where("gain", &two).empty());
    CHECK(src.where("joints.a.min", &sixteen) == "p.lua:5");
    CHECK(src.where("rate", nullptr) == "p.lua");  // two constructors write it: which one counts is not in the text
}

TEST_CASE("a list holds what the file wrote when every entry does and there are no more", "[table_source]") {
    const TableSource src("p.lua", "return {\n  max = { 60, 60, 110, 300 },\n  names = { \"a\", \"b\" },\n"
                                   "  contact = { 0/0, -44 },\n  from = other,\n}\n");
    const ParamValue written{std::vector<std::int64_t>{60, 60, 110, 300}}, changed{std::vector<std::int64_t>{200, 60, 110, 300}},
        longer{std::vector<std::int64_t>{60, 60, 110, 300, 1}}, shorter{std::vector<std::int64_t>{60, 60}};
    CHECK(src.where("max", &written) == "p.lua:2");
    CHECK(src.where("max", &changed).empty());  // e.g. hand.params.max = { 200, ... } in a file that includes this one
    CHECK(src.where("max", &longer).empty());
    CHECK(src.where("max", &shorter).empty());
    const ParamValue names{std::vector<std::string>{"a", "b"}}, contact{std::vector<double>{std::nan(""), -44}};
    CHECK(src.where("names", &names) == "p.lua:3");
    CHECK(src.where("contact", &contact) == "p.lua:4");  // 0/0 is an expression: not checked, not refused
    CHECK(src.where("from", &names).empty());            // a list the text does not spell out
    CHECK(rollsense::nearest_site({{"max", ""}, {"", "x"}}, "max", "root.lua") == "root.lua");
}

TEST_CASE("nearest_site and key_named_in", "[table_source]") {
    const std::map<std::string, std::string> sites{{"joints", "a.lua:3"}, {"joints.palm", "b.lua:9"}};
    CHECK(rollsense::nearest_site(sites, "joints.palm.min", "p.lua") == "b.lua:9");
    CHECK(rollsense::nearest_site(sites, "joints.winch", "p.lua") == "a.lua:3");
    CHECK(rollsense::nearest_site(sites, "clock", "p.lua") == "p.lua");
    const std::map<std::string, ParamValue> keys{{"cell_angles", 1.0}, {"joint", 1.0}};
    REQUIRE(rollsense::key_named_in("cell_angles is empty", keys));
    CHECK(*rollsense::key_named_in("cell_angles is empty", keys) == "cell_angles");
    CHECK(*rollsense::key_named_in("key 'joint' must be a string", keys) == "joint");
    CHECK(*rollsense::key_named_in("joint: set cell_angles too", keys) == "joint");  // the first named
    CHECK_FALSE(rollsense::key_named_in("joints are wrong", keys));  // a word, not a part of one
}

// Fuzzing review: key paths are kept whole, so a file nesting tables under long
// names and then writing many fields asked for memory quadratic in its size.
TEST_CASE("a file whose key paths would take too much memory gives no lines, not gigabytes", "[table_source]") {
    const std::string name(2000, 'k');
    std::string text = "return { small = 1, ";
    for (int level = 0; level < 150; ++level) text += name + " = { ";  // paths of 300,000 bytes
    for (int field = 0; field < 200; ++field) text += "f" + std::to_string(field) + " = 1, ";
    for (int level = 0; level < 150; ++level) text += "} ";
    text += "}";
    const TableSource src("big.lua", text);
    CHECK(src.where("small", nullptr).empty());  // gave up: the caller names the file only
    const TableSource fits("ok.lua", "return { small = 1, " + name + " = { f = 2 } }");
    CHECK(fits.where("small", nullptr) == "ok.lua:1");
}

// Review: a key written twice named its file as the place of a value that a
// statement elsewhere had set since.
TEST_CASE("a key written twice is not known to hold the table's value", "[table_source]") {
    const TableSource src("b.lua", "local a = { rate = 30 }\nreturn { rate = 31.1, port = setting('port', 'x') }");
    const ParamValue later = -5.0;
    CHECK(src.where("rate", nullptr) == "b.lua");  // asked without a value: written here, line unknown
    CHECK(src.where("rate", &later).empty());      // with one: the caller names the file that set it
    CHECK(src.where("port", &later) == "b.lua:2"); // an expression is taken as written
}
