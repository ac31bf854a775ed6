// Every fault gives the documented error (at configure) or invalid-sample
// reason (while sampling) — never a silent zero.
#include <catch2/catch.hpp>

#include <cerrno>

#include "mpl115a_test_rig.hpp"

using namespace rollsense;
using namespace mpl115a_test;
using rollsense::hal::Mpl115aFault;

namespace {
bool is_nan(double v) { return std::isnan(v); }
}  // namespace

TEST_CASE("configure: a missing sensor names the channel, the slot and the probe command", "[mpl115a][faults]") {
    Rig rig("fault-missing");
    rig.strip->set_slot_missing(1, true);
    plugins::Mpl115aSensor s;
    auto st = s.on_configure(params(rig.spec), {});
    REQUIRE_FALSE(st.ok());
    CHECK(st.code() == ErrorCode::hardware_fault);
    CHECK_THAT(st.message(), Catch::Contains("channel ch2") && Catch::Contains("select 0x01") &&
                                 Catch::Contains("NACK") && Catch::Contains("rollsense probe i2c fake:fault-missing"));
}

TEST_CASE("configure: a dead chip (NACK at 0x60)", "[mpl115a][faults]") {
    Rig rig("fault-dead");
    rig.strip->chip(2).set_fault(Mpl115aFault::nack);
    plugins::Mpl115aSensor s;
    auto st = s.on_configure(params(rig.spec), {});
    REQUIRE_FALSE(st.ok());
    CHECK(st.code() == ErrorCode::hardware_fault);
    CHECK_THAT(st.message(), Catch::Contains("channel ch3") && Catch::Contains("no MPL115A at 0x60"));
}

TEST_CASE("configure: no strip on the bus", "[mpl115a][faults]") {
    auto bus = rollsense::hal::FakeI2cBus::get("fault-empty");
    bus->reset();
    plugins::Mpl115aSensor s;
    auto st = s.on_configure(params("fake:fault-empty"), {});
    REQUIRE_FALSE(st.ok());
    CHECK_THAT(st.message(), Catch::Contains("no TakkStrip answers the all-strips address 0x06 on fake:fault-empty") &&
                                 Catch::Contains("rollsense probe i2c"));
}

TEST_CASE("configure: missing bus node and unsuitable adapters", "[mpl115a][faults]") {
    plugins::Mpl115aSensor s;
    auto missing = s.on_configure(params("/dev/i2c-247"), {});
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.code() == ErrorCode::not_found);
    CHECK_THAT(missing.message(), Catch::Contains("bus '/dev/i2c-247'") &&
                                      Catch::Contains("bus = \"fake:strip\", simulate = true"));

    Rig rig("fault-adapter");
    rig.bus->set_functionality({true, false, 0});
    auto no_quick = s.on_configure(params(rig.spec), {});
    CHECK(no_quick.code() == ErrorCode::unsupported);
    CHECK_THAT(no_quick.message(), Catch::Contains("quick commands"));
}

TEST_CASE("sampling: a chip that stops answering marks the frame invalid, other channels stay valid", "[mpl115a][faults]") {
    Rig rig("fault-runtime-nack");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec), {}).ok());
    REQUIRE(s.on_activate().ok());
    REQUIRE(s.start_recording({}).ok());
    REQUIRE(read_frame(s).valid);

    rig.strip->chip(1).set_fault(Mpl115aFault::nack);
    auto f = read_frame(s);
    CHECK_FALSE(f.valid);
    CHECK_THAT(f.reason, Catch::StartsWith("ch2: ") && Catch::Contains("0x60") && Catch::Contains("NACK"));
    CHECK(is_nan(f.values[1]));  // not a silent zero
    CHECK(std::isfinite(f.values[0]));
    CHECK(std::isfinite(f.values[2]));
    CHECK_FALSE(rig.strip->selected(1));

    rig.strip->chip(1).set_fault(Mpl115aFault::none);  // it comes back
    CHECK(read_frame(s).valid);
}

TEST_CASE("sampling: a sensor that disappears from the strip", "[mpl115a][faults]") {
    Rig rig("fault-runtime-missing");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.strip->set_slot_missing(2, true);
    auto f = read_frame(s);
    CHECK_FALSE(f.valid);
    CHECK_THAT(f.reason, Catch::Contains("ch3: selecting strip 0 slot 2 (select 0x02)"));
    CHECK(is_nan(f.values[2]));
}

TEST_CASE("sampling: a stuck ADC is detected after stuck_samples identical readings", "[mpl115a][faults]") {
    Rig rig("fault-stuck");
    // Healthy chips see a slow pressure ramp, so their readings change every sample.
    for (int slot = 0; slot < 3; ++slot)
        rig.strip->chip(slot).set_pressure_source([slot](double t) { return 100.0 + slot + 50.0 * t; });
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"stuck_samples", 5}}), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.strip->chip(0).set_fault(Mpl115aFault::stuck);
    int first_invalid = -1;
    rollsense::Frame last;
    for (int i = 0; i < 10; ++i) {
        last = read_frame(s);
        CHECK(std::isfinite(last.values[1]));
        CHECK(std::isfinite(last.values[2]));
        if (!last.valid && first_invalid < 0) first_invalid = i;
    }
    // The first reading after the fault is the last good one repeated; then
    // repeats 1..5: the 6th identical reading (index 5) is flagged.
    CHECK(first_invalid == 5);
    CHECK_FALSE(last.valid);
    CHECK_THAT(last.reason, Catch::StartsWith("ch1: ADC stuck") && Catch::Contains("stopped converting"));
    CHECK(is_nan(last.values[0]));
}

TEST_CASE("sampling: a transient bus error is retried, and reported without retries", "[mpl115a][faults]") {
    Rig rig("fault-transient");
    plugins::Mpl115aSensor s;

    REQUIRE(s.on_configure(params(rig.spec, {{"retries", 1}}), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.bus->inject_errno(EIO, 1);
    CHECK(read_frame(s).valid);

    REQUIRE(s.on_configure(params(rig.spec, {{"retries", 0}}), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.bus->inject_errno(EIO, 1);
    auto f = read_frame(s);
    CHECK_FALSE(f.valid);
    CHECK_THAT(f.reason, Catch::Contains("starting the conversion") && Catch::Contains("I/O error"));
    for (double v : f.values) CHECK(is_nan(v));
    CHECK(read_frame(s).valid);  // the next sample is fine again
}

TEST_CASE("sampling: a hung bus (timeouts) invalidates every channel with the reason", "[mpl115a][faults]") {
    Rig rig("fault-timeout");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.bus->inject_errno(ETIMEDOUT, 1000);
    auto f = read_frame(s);
    CHECK_FALSE(f.valid);
    CHECK_THAT(f.reason, Catch::Contains("timed out") && Catch::Contains("fake:fault-timeout"));
    rig.bus->inject_errno(0, 0);
}

TEST_CASE("no baseline can be taken from a dead chip: start_recording fails, naming it", "[mpl115a][faults]") {
    Rig rig("fault-baseline");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec), {}).ok());
    rig.strip->chip(0).set_fault(Mpl115aFault::nack);
    auto st = s.start_recording({});
    REQUIRE_FALSE(st.ok());
    CHECK(st.code() == ErrorCode::hardware_fault);
    CHECK_THAT(st.message(), Catch::Contains("no baseline for channel ch1") && Catch::Contains("NACK"));
}

// ---- issue 22: faults injected from the profile (inject = {...}) into the
// strip the plugin models itself (simulate = true), and the run-ending fault.

namespace {

rollsense::ParamSet simulated(const std::string& bus_name, rollsense::ValueMap extra) {
    rollsense::hal::FakeI2cBus::get(bus_name)->reset();
    extra["simulate"] = true;
    return params("fake:" + bus_name, std::move(extra));
}

rollsense::Status read_at(rollsense::Sensor& s, double t, rollsense::Frame& f) {
    rollsense::SampleInput in;
    in.time = t;
    f = {};
    f.time = t;
    f.values.assign(s.channels().size(), 0.0);
    return s.read(in, f);
}

}  // namespace

TEST_CASE("inject: a chip that NACKs from time T, fault_after samples later the run ends naming it",
          "[mpl115a][faults][inject]") {
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(simulated("inject-nack", {{"inject", std::vector<std::string>{"ch2:nack:1.0"}},
                                                     {"fault_after", 3}}),
                           {})
                .ok());
    REQUIRE(s.on_activate().ok());
    REQUIRE(s.start_recording({}).ok());
    rollsense::Frame f;
    REQUIRE(read_at(s, 0.9, f).ok());
    CHECK(f.valid);  // not yet due
    for (double t : {1.0, 1.1}) {
        INFO("t = " << t);
        REQUIRE(read_at(s, t, f).ok());  // a glitch so far: the sample is invalid, the run goes on
        CHECK_FALSE(f.valid);
        CHECK(is_nan(f.values[1]));
        CHECK(std::isfinite(f.values[0]));
    }
    const auto st = read_at(s, 1.2, f);
    REQUIRE_FALSE(st.ok());
    CHECK(st.code() == ErrorCode::hardware_fault);
    CHECK_THAT(st.message(), Catch::Contains("channel ch2, strip 0 slot 1 (select 0x01)") &&
                                 Catch::Contains("no valid reading for 3 samples in a row") &&
                                 Catch::Contains("NACK") && Catch::Contains("rollsense probe i2c fake:inject-nack"));
    // The model goes with the sensor: a new configure finds a healthy strip.
    REQUIRE(s.on_cleanup().ok());
    plugins::Mpl115aSensor again;
    REQUIRE(again.on_configure(params("fake:inject-nack", {{"simulate", true}}), {}).ok());
    REQUIRE(again.start_recording({}).ok());
    CHECK(read_frame(again, 2.0).valid);
}

TEST_CASE("inject: a stuck ADC is flagged after stuck_samples, across recordings, then ends the run",
          "[mpl115a][faults][inject]") {
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(simulated("inject-stuck", {{"inject", std::vector<std::string>{"ch1:stuck:0.5"}},
                                                      {"stuck_samples", 8},
                                                      {"fault_after", 4}}),
                           {})
                .ok());
    REQUIRE(s.on_activate().ok());
    REQUIRE(s.start_recording({}).ok());
    rollsense::Frame f;
    double t = 0;
    for (; t < 0.5; t += 0.1) REQUIRE(read_at(s, t, f).ok());
    CHECK(f.valid);  // the model's ADC noise (0.5 counts): healthy readings change
    // A short recording (a roll shorter than stuck_samples) does not hide it:
    // the count goes on across the next start of a recording.
    for (int i = 0; i < 5; ++i, t += 0.1) REQUIRE(read_at(s, t, f).ok());
    CHECK(f.valid);
    REQUIRE(s.start_recording({}).ok());
    rollsense::Status st;
    int reads = 5;
    for (; reads < 40 && st.ok(); ++reads, t += 0.1) st = read_at(s, t, f);
    REQUIRE_FALSE(st.ok());
    // From the fault on (read 0) every read repeats the last good words:
    // read r is repeat r + 1, flagged from repeat 8 (read 7), and the 4th
    // failing sample (read 10) ends it.
    CHECK(reads == 11);
    CHECK(st.code() == ErrorCode::hardware_fault);
    CHECK_THAT(st.message(), Catch::Contains("channel ch1") && Catch::Contains("ADC stuck") &&
                                 Catch::Contains("no valid reading for 4 samples in a row"));
}

TEST_CASE("inject: malformed entries and a strip the sensor does not model are refused, naming the entry",
          "[mpl115a][faults][inject]") {
    for (const char* bad : {"ch2:nack", "ch9:nack:1", "ch2:melt:1", "ch2:nack:-1", "ch2:nack:soon"}) {
        INFO(bad);
        plugins::Mpl115aSensor s;
        auto st = s.on_configure(simulated("inject-bad", {{"inject", std::vector<std::string>{bad}}}), {});
        REQUIRE_FALSE(st.ok());
        CHECK(st.code() == ErrorCode::invalid_argument);
        CHECK_THAT(st.message(), Catch::StartsWith(std::string("inject '") + bad + "'"));
    }
    Rig rig("inject-rig");  // a strip attached by the test, not by the sensor
    plugins::Mpl115aSensor s;
    auto st = s.on_configure(params(rig.spec, {{"inject", std::vector<std::string>{"ch1:nack:1"}}}), {});
    REQUIRE_FALSE(st.ok());
    CHECK_THAT(st.message(), Catch::Contains("simulate = true"));
}

TEST_CASE("fault_after = 0 keeps the old behaviour: invalid samples, the run goes on", "[mpl115a][faults]") {
    Rig rig("fault-after-off");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"fault_after", 0}}), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.strip->chip(0).set_fault(Mpl115aFault::nack);
    for (int i = 0; i < 200; ++i) CHECK_FALSE(read_frame(s).valid);
}
