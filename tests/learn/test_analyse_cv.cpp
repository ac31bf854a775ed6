// rs.analyse with grouped and blocked CV inside a run of the simulated hand:
// the figures come back beside random k-fold, and a grouping that is the
// class (one mounting per object) is refused with the docs' explanation.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "run_command.hpp"
#include "temp_dir.hpp"

TEST_CASE("rs.analyse runs blocked and speed-grouped CV beside random k-fold", "[learn][lua][cv_scheme]") {
    rollsense::testing::TempDir dir("rollsense-analyse-cv");
    const auto script = dir.path() / "cv.lua";
    std::ofstream(script) << R"(
local rs = require "rollsense"
local etroll = require "etroll"
rs.on_cleanup(etroll.park)
for _, object in ipairs{ "C1", "C3", "H2" } do
  local index = 0
  for _, speed in ipairs{ 10, 20 } do
    for r = 1, 4 do
      etroll.run_trial{ object = object, speed = speed, repetition = r, mount = object .. "-1", index_in_mount = index }
      index = index + 1
    end
  end
end
local result = rs.analyse{ folds = 2, repeats = 1, params = { learners = 5 }, cv = "blocked,grouped", block = 2,
                           group_by = "speed" }
assert(#result.cv == 2, "two schemes, got " .. #result.cv)
assert(result.cv[1].id == "blocked:2", result.cv[1].id)
assert(result.cv[2].id == "grouped:speed", result.cv[2].id)
assert(result.cv[2].accuracy >= 0 and result.cv[2].accuracy <= 1)
rs.log("blocked " .. result.cv[1].accuracy .. ", by speed " .. result.cv[2].accuracy)
local ok, err = pcall(rs.analyse, { folds = 2, repeats = 1, cv = "grouped", group_by = "mount", tag = "mount" })
assert(not ok and tostring(err):find("no training fold ever sees that class", 1, true), tostring(err))
ok, err = pcall(rs.analyse, { cv = "grouped" })
assert(not ok and tostring(err):find("group_by", 1, true), tostring(err))
)";
    const auto out = dir.path() / "run";
    const auto run = rollsense::testing::run_rollsense("run " + script.string() + " --profile sim --seed 4 --out " +
                                                       out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("blocked ") && Catch::Contains(", by speed "));
    std::ifstream json(out / "evaluation.json");
    const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
    CHECK_THAT(text, Catch::Contains("\"cv_schemes\"") && Catch::Contains("\"id\": \"blocked:2\"") &&
                         Catch::Contains("\"group_by\": \"speed\""));
    std::ifstream manifest(out / "manifest.csv");
    const std::string rows((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
    CHECK_THAT(rows, Catch::Contains("H2-v20-r004,trials/H2-v20-r004.csv,H2,20,4,") &&
                         Catch::Contains(",H2-1,7,\n"));  // mount, index_in_mount, an empty extra
}
