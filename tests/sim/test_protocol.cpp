// The paper's protocol in the simulation (docs/simulation.md "Protocol"): one
// printed specimen per object, mounted once for its rolls. Every draw is a pure
// function of (device seed, object, mount, index in mount, trial seed), never of
// the order trials are recorded in, so --resume and --shard stay byte-identical.
#include <catch2/catch.hpp>

#include <cmath>

#include "roll_driver.hpp"
#include "sim_model.hpp"
#include "sim_schema.hpp"
#include "sim_sensor.hpp"

using namespace rollsense;
using namespace rollsense::sim;

namespace {

ObjectSpec nominal(const char* id, int sides, double side, double diameter) {
    ObjectSpec o;
    o.id = id;
    o.sides = sides;
    o.side = side;
    o.diameter = diameter;
    if (sides > 0) {
        o.edge_radius_min = 0.3;
        o.edge_radius_max = 1.5;
    }
    return o;
}

std::unique_ptr<SimSensor> configured(std::map<std::string, ParamValue> raw = {}) {
    auto p = validate_params(sim_schema(), raw, "test");
    REQUIRE(p.ok());
    PluginContext c;
    c.instance = "tactile";
    c.share_dir = ROLLSENSE_SHARE_DIR;
    auto s = std::make_unique<SimSensor>();
    REQUIRE(s->on_configure(p.value(), c).ok());
    return s;
}

bench::Recording roll(SimSensor& s, const TrialInfo& t) {
    bench::Recording rec;
    auto st = bench::record_roll(s, t, {}, rec);
    INFO(st.message());
    REQUIRE(st.ok());
    return rec;
}

TrialInfo mounted(const std::string& mount, long index, std::uint64_t seed = 7) {
    return TrialInfo{"C2-test", "C2", "10", 1, seed, {{"mount", mount}, {"index_in_mount", std::to_string(index)}}};
}

}  // namespace

TEST_CASE("a specimen is its object within the printing tolerance, fixed per device seed", "[sim][protocol]") {
    SimParameters p;
    const auto c = nominal("C2", 0, 0.0, 27.0);
    const auto a = make_specimen(p, c);
    CHECK(std::abs(a.diameter - 27.0) <= p.specimen_size_tolerance);
    CHECK(a.diameter != 27.0);
    CHECK(make_specimen(p, c).diameter == a.diameter);  // the same specimen every trial
    const auto prism = make_specimen(p, nominal("P1", 5, 13.0, 22.1));
    CHECK(std::abs(prism.side - 13.0) <= p.specimen_size_tolerance);
    CHECK(prism.diameter / prism.side == Approx(22.1 / 13.0));
    SimParameters other = p;
    other.device_seed = 2;
    CHECK(make_specimen(other, c).diameter != a.diameter);
    p.specimen_size_tolerance = 0.0;
    CHECK(make_specimen(p, c).diameter == 27.0);
}

TEST_CASE("a prism's edge radii belong to its specimen, not to the trial", "[sim][protocol]") {
    SimParameters p;
    const DeviceState device = make_device(p);
    const auto h1 = nominal("H1", 6, 13.0, 26.0);
    TrialModel a(p, device, &h1, 1), b(p, device, &h1, 2);
    CHECK(a.draws().edge_radius == b.draws().edge_radius);
    CHECK(a.draws().start_centre != b.draws().start_centre);  // the placement still varies per trial
    p.specimen_edges = false;
    TrialModel c(p, device, &h1, 1), d(p, device, &h1, 2);
    CHECK(c.draws().edge_radius != d.draws().edge_radius);
}

TEST_CASE("mount effects: off by default, and a pure function of object, mount and index", "[sim][protocol]") {
    SimParameters p;
    const DeviceState device = make_device(p);
    const auto c2 = nominal("C2", 0, 0.0, 27.0);
    TrialModel none(p, device, &c2, 5), first(p, device, &c2, 5, {"C2-1", 0}), later(p, device, &c2, 5, {"C2-2", 149});
    CHECK(first.draws().start_centre == none.draws().start_centre);
    CHECK(later.draws().force_factor == none.draws().force_factor);

    p.mount_start_sigma = 2.0;
    p.mount_force_log_sigma = 0.1;
    p.mount_force_trend = 0.05;
    TrialModel m1(p, device, &c2, 5, {"C2-1", 0}), m1again(p, device, &c2, 5, {"C2-1", 0});
    TrialModel m2(p, device, &c2, 5, {"C2-2", 0}), m1late(p, device, &c2, 5, {"C2-1", 100});
    CHECK(m1.draws().start_centre == m1again.draws().start_centre);
    CHECK(m1.draws().force_factor == m1again.draws().force_factor);
    CHECK(m1.draws().start_centre != m2.draws().start_centre);
    CHECK(m1late.draws().start_centre == m1.draws().start_centre);  // the mounting is the same
    CHECK(m1late.draws().force_factor == Approx(m1.draws().force_factor * 1.05));
}

TEST_CASE("the sim sensor reads mount and index_in_mount from the trial, in any order", "[sim][protocol]") {
    auto s = configured({{"mount_start_sigma", 3.0}, {"mount_force_trend", 0.2}});
    const auto late = roll(*s, mounted("C2-1", 120));
    const auto early = roll(*s, mounted("C2-1", 0));
    const auto other = roll(*s, mounted("C2-2", 0));
    auto fresh = configured({{"mount_start_sigma", 3.0}, {"mount_force_trend", 0.2}});
    CHECK(roll(*fresh, mounted("C2-1", 0)).channels[1] == early.channels[1]);  // not a function of what came before
    CHECK(roll(*fresh, mounted("C2-1", 120)).channels[1] == late.channels[1]);
    CHECK(early.channels[1] != late.channels[1]);
    CHECK(early.channels[1] != other.channels[1]);

    bench::Recording rec;
    TrialInfo bad{"C2-bad", "C2", "10", 1, 7, {{"mount", "C2-1"}, {"index_in_mount", "first"}}};
    auto st = bench::record_roll(*s, bad, {}, rec);
    REQUIRE_FALSE(st.ok());
    CHECK_THAT(st.message(), Catch::Contains("index_in_mount 'first' is not an integer"));
    CHECK_THAT(st.message(), Catch::Contains("C2-bad"));
}
