// A series model end to end inside a run: rs.analyse with minirocket first
// trains and saves it (on the trials the input step selects), and
// rs.classifier{...}:identify() (the plugin the model file names) prepares a fresh recording with the same
// series rule and names the object. A model trained with series_amplitude =
// "z_per_channel" records it in its file: identify() applies it unasked, and
// refuses an amplitude that contradicts it.
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
-- No classifier given: the plugin the model's first line names (plugin review: the stock default, bagged_trees,
-- was asked to read it and refused it).
local clf = rs.classifier{ model = result.model }
-- A file that names no plugin is the stock default's to refuse, as before.
local ok_m, err_m = pcall(rs.classifier, { model = result.model:match("(.*)/") .. "/features.csv" })
assert(not ok_m and tostring(err_m):find("is not a rollsense bagged-trees model", 1, true), tostring(err_m))
local z = rs.analyse{ classifiers = { "minirocket" }, folds = 2, repeats = 1, trials = "all",
                      params = { num_features = 168 }, model = "z.rsm", tag = "z", series_amplitude = "z_per_channel" }
local clf_z = rs.classifier{ model = z.model, classifier = "minirocket" }
-- Prefix models record the rule too (rs.prefix_models, identify_early.lua).
local early = rs.prefix_models{ dataset = z.model:match("(.*)/"), classifier = "minirocket:num_features=168",
                                fractions = { 1 }, name = "zp", series_amplitude = "z_per_channel" }
local clf_p = rs.classifier{ model = early.models[1].path, classifier = "minirocket" }
-- User review: two fractions of one whole percent saved one model over the other, both paths returned.
local ok_f, err_f = pcall(rs.prefix_models, { dataset = z.model:match("(.*)/"), classifier = "minirocket",
                                              fractions = { 0.5, 0.12, 0.124 } })
assert(not ok_f and tostring(err_f):find("fractions[2] (0.12) and fractions[3] (0.124) would both be saved as " ..
                                         "NAME-f012.rsm", 1, true), tostring(err_f))
-- Review (user journeys) item 9: a feature model ignored a mistyped option.
local trees = rs.analyse{ classifiers = { "bagged_trees" }, folds = 2, repeats = 1, model = "trees.rsm", tag = "trees" }
local clf_t = rs.classifier{ model = trees.model, classifier = "bagged_trees" }
rs.trial{ object = "P1", speed = 15, repetition = 99, id = "live" }
etroll.open(); etroll.clamp(); etroll.roll(15)
local answer, why = clf:identify()
local unasked, told = clf_z:identify(), clf_z:identify{ series_amplitude = "z_per_channel" }
local ok_g, err_g = pcall(clf_z.identify, clf_z, { series_amplitude = "global_scale" })
local p_unasked = clf_p:identify{ open_end = true }
local p_told = clf_p:identify{ open_end = true, series_amplitude = "z_per_channel" }
local ok_t, err_t = pcall(clf_t.identify, clf_t, { open_ned = true })
local ok_b, err_b = pcall(clf_t.identify, clf_t, { open_end = 1 })
-- The contact's clock a stopping rule reads (identify_early.lua), after a whole roll.
local progress = clf:contact_progress(early.units)
local ok_u, err_u = pcall(clf.contact_progress, clf, 0)
etroll.return_to_start(); etroll.release(); rs.end_trial()
assert(answer, "identify refused: " .. tostring(why))
local sum = 0
for _, s in pairs(answer.scores) do sum = sum + s end
assert(math.abs(sum - 1) < 1e-9, "scores sum to " .. sum)
rs.log("identified " .. answer.object)
assert(unasked and told, "the z_per_channel model refused the roll")
for name, s in pairs(told.scores) do
  assert(unasked.scores[name] == s, name .. ": " .. tostring(unasked.scores[name]) .. " without the option, " .. s .. " with it")
end
assert(not ok_g and tostring(err_g):find("trained with 'z_per_channel'"), tostring(err_g))
assert(p_unasked and p_told, "the z_per_channel prefix model refused the roll")
for name, s in pairs(p_told.scores) do assert(p_unasked.scores[name] == s, "prefix model, " .. name) end
rs.log("z_per_channel model: recorded rule applied")
-- (a prism roll can be well short of or past the nominal one: its first bump's width varies with its face)
assert(early.units > 1 and progress and progress > 0, "progress " .. tostring(progress))
assert(not ok_u and tostring(err_u):find("units must be > 0"), tostring(err_u))
assert(not ok_t and tostring(err_t):find("identify: unknown option 'open_ned'", 1, true) and
       tostring(err_t):find("options: series_amplitude, open_end", 1, true), tostring(err_t))
assert(not ok_b and tostring(err_b):find("option 'open_end' must be true or false", 1, true), tostring(err_b))
-- A wrong amplitude word is an error naming the choices.
local ok, err = pcall(clf.identify, clf, { series_amplitude = "loud" })
assert(not ok and tostring(err):find("z_per_channel"), tostring(err))
)";
    const auto out = dir.path() / "run";
    const auto run = rollsense::testing::run_rollsense("run " + script.string() + " --profile sim --seed 4 --out " +
                                                       out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("identified ") && Catch::Contains("z_per_channel model: recorded rule applied"));
    CHECK(std::filesystem::exists(out / "rocket.rsm"));
    std::ifstream prefix_model(out / "zp-f100.rsm");
    std::string line;
    while (std::getline(prefix_model, line) && line.rfind("series_rule", 0) != 0) {}
    CHECK_THAT(line, Catch::StartsWith("series_rule length=128 ") && Catch::Contains(" amplitude=z_per_channel "));
    CHECK(std::filesystem::exists(out / "evaluation-rocket.json"));
    CHECK(std::filesystem::exists(out / "report-rocket.html"));
}
