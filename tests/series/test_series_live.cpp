// A series model end to end inside a run: rs.analyse with minirocket first
// trains and saves it (on the trials the input step selects), and
// rs.classifier{...}:identify() prepares a fresh recording with the same
// series rule and names the object.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "run_command.hpp"
#include "temp_dir.hpp"

TEST_CASE("rs.analyse trains a minirocket model and clf:identify() uses it on a live roll", "[series][lua]") {
    rollsense::testing::TempDir dir("rollsense-series-live");
    const auto script = dir.path() / "live.lua";
    std::ofstream(script) << R"(
local rs = require "rollsense"
local etroll = require "etroll"
rs.on_cleanup(etroll.park)
for _, object in ipairs{ "C1", "P1", "H2" } do
  for r = 1, 4 do etroll.run_trial{ object = object, speed = 15, repetition = r } end
end
local result = rs.analyse{ classifiers = { "minirocket" }, folds = 2, repeats = 1, trials = "all",
                           params = { num_features = 168 }, model = "rocket.rsm", tag = "rocket" }
local clf = rs.classifier{ model = result.model, classifier = "minirocket" }
rs.trial{ object = "P1", speed = 15, repetition = 99, id = "live" }
etroll.open(); etroll.clamp(); etroll.roll(15)
local answer, why = clf:identify()
etroll.return_to_start(); etroll.release(); rs.end_trial()
assert(answer, "identify refused: " .. tostring(why))
local sum = 0
for _, s in pairs(answer.scores) do sum = sum + s end
assert(math.abs(sum - 1) < 1e-9, "scores sum to " .. sum)
rs.log("identified " .. answer.object)
-- A wrong amplitude word is an error naming the choices.
local ok, err = pcall(clf.identify, clf, { series_amplitude = "loud" })
assert(not ok and tostring(err):find("z_per_channel"), tostring(err))
)";
    const auto out = dir.path() / "run";
    const auto run = rollsense::testing::run_rollsense("run " + script.string() + " --profile sim --seed 4 --out " +
                                                       out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("identified "));
    CHECK(std::filesystem::exists(out / "rocket.rsm"));
    CHECK(std::filesystem::exists(out / "evaluation-rocket.json"));
    CHECK(std::filesystem::exists(out / "report-rocket.html"));
}
