// The trial-id format has one home (rollsense::trial_id); rs.trial_id{} and the
// id rs.trial{} gives a trial without one both come from it.
#include <catch2/catch.hpp>

#include "rollsense/trial_id.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::testing;

TEST_CASE("a trial id is object, speed and the repetition in three digits", "[experiment][trial_id]") {
    CHECK(trial_id("C1", "10", 7) == "C1-v10-r007");
    CHECK(trial_id("H2", "12.5", 50) == "H2-v12.5-r050");
    CHECK(trial_id("X10", "20", 1234) == "X10-v20-r1234");  // wider numbers are not cut
}

TEST_CASE("rs.trial_id names the trial rs.trial begins, and refuses a trial without an object",
          "[experiment][trial_id]") {
    TempDir dir("rollsense-trial-id");
    write_file(dir / "ids.lua", R"(
local rs = require "rollsense"
local key = { object = "C2", speed = 15, repetition = 3 }
local expected = rs.trial_id(key)
assert(expected == "C2-v15-r003", "rs.trial_id gave " .. expected)
local id = rs.trial(key)
assert(id == expected, "rs.trial gave " .. id .. ", rs.trial_id " .. expected)
rs.end_trial()
local ok, err = pcall(rs.trial_id, { speed = 10 })
assert(not ok and err:find("give an object"), "expected an error, got " .. tostring(err))
print("trial ids agree")
)");
    const auto run = run_rollsense("run " + (dir / "ids.lua").string() + " --profile sim --out " +
                                   (dir / "out").string());
    INFO(run.output);
    CHECK(run.status == 0);
    CHECK(run.output.find("trial ids agree") != std::string::npos);
}
