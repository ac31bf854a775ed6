// The replay sensor passes the sensor conformance suite, on a recorded dataset
// longer than the suite's recording and on one shorter (frames past the end
// are invalid with their reason, or hold the last sample).
#include <catch2/catch.hpp>

#include "rollsense/testing/conformance.hpp"
#include "replay_fixture.hpp"

using namespace rollsense;

namespace {
testing::SensorConformance conformance_on(const rt::TempDir& dir, std::map<std::string, ParamValue> extra = {}) {
    testing::SensorConformance c;
    c.make = [] { return std::make_unique<plugins::replay::ReplaySensor>(); };
    auto params = rt::replay_params(dir / "ds", std::move(extra));
    REQUIRE(params.ok());
    c.params = *params;
    c.context.instance = "tactile";
    c.context.virtual_time = true;
    // The finger sweeps as it did in the recording, so no roll warning.
    c.joint_names = {"sensing_finger"};
    c.joints = [period = c.period](double t) {
        JointState s;
        s.position = rt::sweep_angle(static_cast<std::size_t>(std::lround(t / period)));
        return std::vector<JointState>{s};
    };
    return c;
}
}  // namespace

TEST_CASE("replay passes the sensor conformance suite", "[replay][conformance]") {
    rt::TempDir dir;
    // The suite's trial is C1 / speed 10 / repetition 1, recorded with 60 samples.
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 60}, {"C2", "10", 1, 30}});
    rt::LogCapture log;
    auto c = conformance_on(dir);
    testing::check_sensor_conformance(c);
    CHECK(log.count("does not match") == 0);
}

TEST_CASE("replay passes conformance when the script records past the recording's end", "[replay][conformance]") {
    rt::TempDir dir;
    rt::write_dataset(dir / "ds", {{"C1", "10", 1, 25}});
    SECTION("past_end = invalid: invalid frames that say why") {
        auto c = conformance_on(dir);
        c.expect_all_valid = false;
        testing::check_sensor_conformance(c);
    }
    SECTION("past_end = hold: the last sample, valid") {
        auto c = conformance_on(dir, {{"past_end", std::string("hold")}});
        testing::check_sensor_conformance(c);
    }
}
