// Lua procedures on the virtual clock: wait/move semantics, concurrent tasks,
// errors with file:line and traceback.
#include <catch2/catch.hpp>

#include "kernel_fixture.hpp"

using namespace rollsense;

namespace {
// Runs a script that reports values with rs.write_output("result.txt", ...).
std::string run_and_read(kt::TempDir& dir, const std::string& script) {
    auto r = kt::run_script(dir, "local rs = require 'rollsense'\n" + script);
    INFO(r.summary.status.message());
    REQUIRE(r.summary.status.ok());
    return kt::read_file(r.out / "result.txt");
}
}  // namespace

TEST_CASE("rs.wait advances the virtual clock by exactly the time asked", "[lua]") {
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        local t0 = rs.now()
        rs.wait(250)
        local t1 = rs.now()
        rs.wait(1000)
        rs.write_output("result.txt", string.format("%.6f %.6f", t1 - t0, rs.now() - t1)))");
    CHECK(out == "0.250000 1.000000");
}

// Review (scripting): a polling loop on rs.wait(0) never let a control period run, so on the virtual clock the joint
// never moved and the run hung; rs.wait(0) now waits for the next control period.
TEST_CASE("rs.wait(0) lets one control period pass so a polling loop sees the joint move", "[lua]") {
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        local f = rs.joint("finger")
        f:move(20, { velocity = 10, wait = false })
        local polls = 0
        while f:position() < 10 do rs.wait(0); polls = polls + 1 end
        rs.write_output("result.txt", string.format("%s %s", tostring(polls > 1), tostring(rs.now() < 2))))");
    CHECK(out == "true true");
}

TEST_CASE("a run of many robot-seconds takes little wall time on the virtual clock", "[lua]") {
    kt::TempDir dir;
    auto r = kt::run_script(dir, "local rs = require 'rollsense'\nrs.wait(600000)\n");
    REQUIRE(r.summary.status.ok());
    CHECK(r.summary.run_time_s == Approx(600.0).margin(0.02));
    CHECK(r.summary.wall_time_s < r.summary.run_time_s);  // not a timing threshold: 600 s cannot pass in real time here
}

TEST_CASE("move waits until the joint arrives, following the servo's profile", "[lua]") {
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        local f = rs.joint("finger")
        local t0 = rs.now()
        f:move(30, { velocity = 30 })                      -- unlimited acceleration: 1 s
        local t1 = rs.now()
        f:move(0, { velocity = 30, acceleration = 60 })    -- trapezoid: 30/30 + 30/60 = 1.5 s
        local t2 = rs.now()
        rs.write_output("result.txt", string.format("%.2f %.2f %.3f %s", t1 - t0, t2 - t1, f:position(), tostring(f:moving()))))");
    double a = 0, b = 0, pos = 1;
    char moving[8] = {};
    REQUIRE(std::sscanf(out.c_str(), "%lf %lf %lf %7s", &a, &b, &pos, moving) == 4);
    // Arrival is noticed at the first control tick (10 ms) after the profile ends.
    CHECK(a >= 1.0);
    CHECK(a <= 1.02);
    CHECK(b >= 1.5);
    CHECK(b <= 1.52);
    CHECK(pos == Approx(0.0).margin(1e-9));
    CHECK(std::string(moving) == "false");
}

TEST_CASE("a move that cannot arrive in time raises a timeout naming the joint", "[lua]") {
    kt::TempDir dir;
    auto r = kt::run_script(dir, R"(local rs = require 'rollsense'
rs.joint("finger"):move(40, { velocity = 1, timeout_ms = 500 })
)");
    REQUIRE_FALSE(r.summary.status.ok());
    CHECK(r.summary.status.code() == ErrorCode::timeout);
    CHECK_THAT(r.summary.status.message(), Catch::Contains("timed out waiting for joint 'finger' to reach 40"));
    CHECK_THAT(r.summary.status.message(), Catch::Contains("script.lua:2:"));
    // rs.wait_joints raises too (unlike rs.wait_until); its timeout reads as given (Lua review: "0.100000 s").
    kt::TempDir other;
    auto w = kt::run_script(other, R"(local rs = require 'rollsense'
local f = rs.joint("finger")
f:move(40, { velocity = 1, wait = false })
rs.wait_joints({ f }, { timeout_ms = 100 })
)");
    CHECK(w.summary.status.code() == ErrorCode::timeout);
    CHECK_THAT(w.summary.status.message(), Catch::Contains("timed out waiting for joints finger to arrive (timeout 0.1 s)") &&
                                               Catch::Contains("script.lua:4:"));
}

TEST_CASE("wait_until returns true when the condition holds and false on timeout", "[lua]") {
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        local f = rs.joint("finger")
        f:move(20, { velocity = 10, wait = false })
        local reached = rs.wait_until(function() return f:position() > 10 end, 5000)
        local t = rs.now()
        local never = rs.wait_until(function() return false end, 300)
        rs.write_output("result.txt", string.format("%s %.1f %s", tostring(reached), t, tostring(never))))");
    CHECK(out == "true 1.0 false");
}

TEST_CASE("spawned tasks run concurrently with the main procedure", "[lua]") {
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        local log = {}
        rs.spawn(function() for i = 1, 3 do rs.wait(100); log[#log + 1] = "b" .. i end end)
        for i = 1, 3 do rs.wait(150); log[#log + 1] = "a" .. i end
        rs.write_output("result.txt", table.concat(log, " ")))");
    // At 300 ms both are due: tasks resume in the order they were created (main first).
    CHECK(out == "b1 a1 b2 a2 b3 a3");
}

TEST_CASE("a script error comes back with file, line and traceback", "[lua]") {
    kt::TempDir dir;
    auto r = kt::run_script(dir, "local rs = require 'rollsense'\n"
                                 "local function inner() local t = nil; return t.field end\n"
                                 "local function outer() inner() end\n"
                                 "outer()\n");
    REQUIRE_FALSE(r.summary.status.ok());
    CHECK(r.summary.status.code() == ErrorCode::script_error);
    const auto& m = r.summary.status.message();
    CHECK_THAT(m, Catch::Contains("script.lua:2: attempt to index a nil value"));
    CHECK_THAT(m, Catch::Contains("stack traceback"));
    CHECK_THAT(m, Catch::Contains("script.lua:3: in"));
    CHECK_THAT(m, Catch::Contains("script.lua:4: in main chunk"));
}

// Review (bad inputs): a mistyped API name gave Lua's "attempt to call a nil
// value (field 'record_strat')", with no hint of the name meant.
TEST_CASE("a name the API does not have is an error at its line naming the nearest one", "[lua]") {
    struct Case { const char* line; const char* says; };
    for (const Case& c : {Case{"rs.record_strat()", "script.lua:2: rs.record_strat does not exist (did you mean "
                                                     "rs.record_start?); docs/scripting.md lists the API"},
                          Case{"local x = rs.wiat", "script.lua:2: rs.wiat does not exist (did you mean rs.wait?)"},
                          Case{"rs.joint('finger'):torqeu(false)",
                               "script.lua:2: joint:torqeu does not exist (did you mean joint:torque?)"},
                          Case{"rs.device('hand'):cal('x')", "script.lua:2: device:cal does not exist (did you mean device:call?)"},
                          Case{"rs.zzzzzzzzzz()", "script.lua:2: rs.zzzzzzzzzz does not exist; docs"}}) {
        INFO(c.line);
        kt::TempDir dir;
        const auto r = kt::run_script(dir, std::string("local rs = require 'rollsense'\n") + c.line + "\n");
        REQUIRE_FALSE(r.summary.status.ok());
        CHECK(r.summary.status.code() == ErrorCode::script_error);
        CHECK_THAT(r.summary.status.message(), Catch::Contains(c.says));
    }
    // Its metatable is the kernel's: a script cannot call the lookup with another table, nor remove it (review: a
    // call with a number crashed liblua). Keys other than names read nil, so ipairs(rs) ends at once.
    {
        kt::TempDir guarded;
        CHECK(run_and_read(guarded, "rs.write_output('result.txt', type(getmetatable(rs)) .. ' ' .. tostring(rs[1]))\n"
                                    "for _ in ipairs(rs) do error('a name') end\n") == "string nil");
        kt::TempDir other;
        const auto r = kt::run_script(other, "local rs = require 'rollsense'\nsetmetatable(rs, nil)\n");
        CHECK_THAT(r.summary.status.message(), Catch::Contains("script.lua:2: cannot change a protected metatable"));
    }
    // rawget tests for a name, and a script may still add its own.
    kt::TempDir dir;
    CHECK(run_and_read(dir, "rs.helper = function() return 'own' end\n"
                            "rs.write_output('result.txt', tostring(rawget(rs, 'analyse_later')) .. ' ' .. rs.helper())\n") ==
          "nil own");
}

TEST_CASE("a syntax error names the line and runs nothing", "[lua]") {
    kt::TempDir dir;
    auto r = kt::run_script(dir, "local rs = require 'rollsense'\nrs.wait(10\n");
    REQUIRE_FALSE(r.summary.status.ok());
    CHECK(r.summary.status.code() == ErrorCode::parse_error);
    CHECK_THAT(r.summary.status.message(), Catch::Contains("script.lua:3:"));
}

TEST_CASE("waiting where a yield would cross C is refused with an explanation", "[lua]") {
    kt::TempDir dir;
    auto r = kt::run_script(dir, R"(local rs = require 'rollsense'
local t = { 3, 1, 2 }
table.sort(t, function(a, b) rs.wait(1); return a < b end)
)");
    REQUIRE_FALSE(r.summary.status.ok());
    CHECK_THAT(r.summary.status.message(), Catch::Contains("cannot wait here"));
}

TEST_CASE("the waiting calls refuse bad arguments before any wait, naming the call and the line", "[lua]") {
    // They only ask the task to wait (the shared wrapper yields): a refusal
    // raises from the call itself, and a move told not to wait returns at once.
    for (const auto& [call, expected] :
         {std::pair{"rs.wait(-1)", "rs.wait: milliseconds must be a number >= 0"},
          std::pair{"rs.joint('finger'):move(10, { mode = 'current' })", "move: mode 'current' is not a position mode"},
          std::pair{"rs.wait_until(42)", "bad argument #1 to 'wait_until'"},
          // Review (user journeys) item 9: names for handles said "bad argument #-1 to 'wait_joints'".
          std::pair{"rs.wait_joints({ 'finger' })", "rs.wait_joints: item 1 is a string, not a joint (rs.joint(name))"},
          std::pair{"rs.save_trial()", "no trial to save: rs.trial{...} first"},
          // Review (scripting): current= was ignored outside current-based position, and a NaN or negative timeout
          // meant "wait forever".
          std::pair{"rs.joint('finger'):move(10, { current = 100 })", "move: current= is the current limit of mode ="},
          std::pair{"rs.wait_until(function() return false end, 0/0)", "rs.wait_until: timeout_ms must be a number >= 0"},
          std::pair{"rs.wait_until(function() return false end, -5)", "rs.wait_until: timeout_ms must be a number >= 0"}}) {
        INFO(call);
        kt::TempDir dir;
        auto r = kt::run_script(dir, std::string("local rs = require 'rollsense'\n") + call + "\n");
        REQUIRE_FALSE(r.summary.status.ok());
        CHECK_THAT(r.summary.status.message(), Catch::Contains(expected) && Catch::Contains("script.lua:2:"));
    }
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        local t0 = rs.now()
        local n = select("#", rs.joint("finger"):move(30, { velocity = 30, wait = false }))
        local t1 = rs.now()
        rs.wait_joints({ rs.joint("finger") })
        local arrived = rs.now() - t1                 -- 1 s, noticed at the next control tick
        rs.write_output("result.txt", string.format("%d %.3f %s %s", n, t1 - t0, tostring(arrived >= 1 and arrived <= 1.02),
                                                    tostring(rs.wait_until(function() return true end, 100)))))");
    CHECK(out == "0 0.000 true true");
}

// Review (user journeys) item 6: Lua counts 0 and "off" as true, so j:torque(0)
// switched a servo's torque on. A switch takes true or false only; and a move
// whose `wait` option is refused has not moved (it was read after the command).
TEST_CASE("a switch takes true or false only: torque 0 or off switches nothing on", "[lua][limits]") {
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        local f = rs.joint("finger")
        f:torque(false)
        local said = {}
        for _, call in ipairs({ function() f:torque(0) end, function() f:torque("off") end, function() f:torque() end,
                                function() rs.controller("palm", "off") end,
                                function() f:move(10, { wait = 0 }) end, function() f:move(10, { wait = {} }) end,
                                function() f:move(10, { velocity = { 20 } }) end,
                                function() f:move(10, { velocity = "fast" }) end }) do
          local ok, err = pcall(call)
          said[#said + 1] = tostring(ok) .. " " .. tostring(err)
        end
        rs.wait(50)  -- the state read next is the servo's, a control period later
        rs.write_output("result.txt", tostring(f:state().torque) .. "\n" .. table.concat(said, "\n")))");
    INFO(out);
    CHECK(out.rfind("false\n", 0) == 0);  // torque still off
    CHECK_THAT(out, Catch::Contains("script.lua:6: bad argument #1 to 'torque' (boolean expected, got number)"));
    CHECK_THAT(out, Catch::Contains("bad argument #1 to 'torque' (boolean expected, got string)"));
    CHECK_THAT(out, Catch::Contains("bad argument #1 to 'torque' (boolean expected, got no value)"));
    CHECK_THAT(out, Catch::Contains("bad argument #2 to 'controller' (boolean expected, got string)"));
    CHECK_THAT(out, Catch::Contains("option 'wait' must be true or false, not 0"));
    // Named by type, not a table's address (user review).
    CHECK_THAT(out, Catch::Contains("option 'wait' must be true or false, not a table"));
    CHECK_THAT(out, Catch::Contains("option 'velocity' must be a finite number, not a table"));
    CHECK_THAT(out, Catch::Contains("option 'velocity' must be a finite number, not 'fast'"));
    CHECK_THAT(out, !Catch::Contains("0x"));
}

TEST_CASE("recording samples sensors and joints at the profile's rate", "[lua]") {
    kt::TempDir dir;
    auto out = run_and_read(dir, R"(
        rs.trial{ object = "X", speed = 1, repetition = 1 }
        rs.record_start()
        rs.wait(1000)
        local n = rs.record_stop()
        local d = rs.recorded()
        rs.write_output("result.txt", string.format("%d %d %.6f", n, #d.ch1, d.time[2])))");
    // 31.1 Hz over one second: samples at 0, 1/31.1, ..., 31/31.1 s (32 samples).
    CHECK(out == "32 32 0.032154");
}
