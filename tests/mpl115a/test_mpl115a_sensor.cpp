// The mpl115a sensor on a modelled strip: discovery and coefficients, the
// select/convert/read sequence and its timing, compensation, baseline, scale.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "mpl115a_test_rig.hpp"
#include "rollsense/hal/takkstrip.hpp"

using namespace rollsense;
using namespace mpl115a_test;
using rollsense::hal::I2cLogEntry;
namespace ms = rollsense::hal::mpl115a;

TEST_CASE("configure discovers the sensors and decodes each one's coefficients", "[mpl115a]") {
    Rig rig("sensor-config");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"sensors", std::vector<std::int64_t>{1, 2, 4}}}), {}).ok());
    auto ch = s.channels();
    REQUIRE(ch.size() == 3);
    CHECK(ch[0].name == "ch1");
    CHECK(ch[2].name == "ch3");
    CHECK(ch[0].unit == "1");
    CHECK_THAT(ch[2].description, Catch::Contains("select 0x04"));

    auto c = s.invoke("coefficients", {});
    REQUIRE(c.ok());
    CHECK(std::get<std::int64_t>(c->at("ch3.select")) == 4);
    CHECK(std::get<double>(c->at("ch1.a0")) == rig.strip->chip(1).coefficients().a0);
    CHECK(std::get<double>(c->at("ch2.c12")) == rig.strip->chip(2).coefficients().c12);
    CHECK(std::get<double>(c->at("ch3.b1")) == rig.strip->chip(4).coefficients().b1);
    // Coefficients are read once, at configure: 8 bytes from register 0x04 per sensor.
    int coefficient_reads = 0;
    for (const auto& e : rig.bus->log())
        if (e.kind == I2cLogEntry::Kind::read && e.address == ms::kAddress && e.data.size() == 8) ++coefficient_reads;
    CHECK(coefficient_reads == 3);
    for (int slot = 0; slot < 6; ++slot) CHECK_FALSE(rig.strip->selected(slot));
}

TEST_CASE("one sample: select all, convert, deselect all, wait, then select-read-deselect each", "[mpl115a][sequence]") {
    // Worst-case chips: the conversion takes the datasheet's maximum, 3 ms.
    Rig rig("sensor-sequence", {.conversion_time = 3e-3});
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"sensors", std::vector<std::int64_t>{0, 1, 2}}}), {}).ok());
    REQUIRE(s.on_activate().ok());
    REQUIRE(s.start_recording({}).ok());
    rig.bus->clear_log();
    const auto f = read_frame(s);
    CHECK(f.valid);

    using K = I2cLogEntry::Kind;
    const auto log = rig.bus->log();
    REQUIRE(log.size() == 3 + 3 * 4);
    // select all → start conversion (0x12 + data byte) → deselect all
    CHECK((log[0].kind == K::quick && !log[0].read_bit && log[0].address == 0x06));
    CHECK((log[1].kind == K::write && log[1].address == 0x60 && log[1].data == std::vector<std::uint8_t>{0x12, 0x00}));
    CHECK((log[2].kind == K::quick && log[2].read_bit && log[2].address == 0x06));
    for (std::uint8_t sensor = 0; sensor < 3; ++sensor) {
        const auto* e = &log[3 + 4 * sensor];
        INFO("sensor " << int(sensor));
        CHECK((e[0].kind == K::quick && !e[0].read_bit && e[0].address == sensor));  // select
        CHECK((e[1].kind == K::write && e[1].address == 0x60 && e[1].data == std::vector<std::uint8_t>{0x00}));
        CHECK((e[2].kind == K::read && e[2].address == 0x60 && e[2].repeated_start && e[2].data.size() == 4));
        CHECK((e[3].kind == K::quick && e[3].read_bit && e[3].address == sensor));  // deselect
    }
    // Timing on the bus clock: the first ADC read starts ≥ 3 ms after the
    // conversion command, and no chip was read while still converting.
    CHECK(log[3].time - log[1].time >= 3e-3);
    for (int slot = 0; slot < 3; ++slot) CHECK(rig.strip->chip(slot).early_reads() == 0);
}

TEST_CASE("the wait follows conversion_time_ms", "[mpl115a][sequence]") {
    Rig rig("sensor-wait");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"conversion_time_ms", 7.5}}), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.bus->clear_log();
    (void)read_frame(s);
    const auto log = rig.bus->log();
    REQUIRE(log.size() > 3);
    const double gap = log[3].time - log[2].time;  // deselect all → first select
    CHECK(gap >= 7.5e-3);
    CHECK(gap < 7.6e-3);  // a wait, not a poll loop: exactly the configured time plus the STOP bit
}

TEST_CASE("values: baseline-subtracted kPa times scale, plus raw kPa and temperature", "[mpl115a][compensation]") {
    Rig rig("sensor-values");
    rig.strip->chip(0).set_pressure_kpa(101.0);
    rig.strip->chip(1).set_pressure_kpa(102.0);
    rig.strip->chip(2).set_pressure_kpa(100.5);
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"raw_channels", true}}), {}).ok());
    const auto ch = s.channels();
    REQUIRE(ch.size() == 9);
    CHECK(ch[3].name == "ch1_kpa");
    CHECK(ch[3].unit == "kPa");
    CHECK(ch[8].name == "ch3_tadc");
    CHECK(ch[8].unit == "count");

    REQUIRE(s.on_activate().ok());
    REQUIRE(s.start_recording({}).ok());
    auto base = s.invoke("baseline", {});
    REQUIRE(base.ok());
    CHECK(std::get<double>(base->at("ch1")) == Approx(101.0).margin(0.07));
    CHECK(std::get<double>(base->at("ch2")) == Approx(102.0).margin(0.07));

    // No contact: ~0 on every channel.
    auto f0 = read_frame(s);
    REQUIRE(f0.valid);
    for (int i = 0; i < 3; ++i) CHECK(f0.values[i] == Approx(0.0).margin(1e-12));

    // Press: +8 kPa on ch2 reads 8/16 = 0.5 units (within one ADC count ≈ 0.126 kPa).
    rig.strip->chip(1).set_pressure_kpa(110.0);
    rig.strip->chip(2).set_temperature_c(30.0);
    auto f1 = read_frame(s);
    REQUIRE(f1.valid);
    CHECK(f1.values[0] == Approx(0.0).margin(1e-12));
    CHECK(f1.values[1] == Approx(0.5).margin(0.126 / 16));
    CHECK(f1.values[4] == Approx(110.0).margin(0.07));
    // The kPa channel is exactly the datasheet formula on the chip's own ADC values.
    const auto adc = rig.strip->chip(1).last_result();
    CHECK(f1.values[4] == ms::pressure_kpa(rig.strip->chip(1).coefficients(), adc));
    CHECK(f1.values[1] == Approx((f1.values[4] - std::get<double>(base->at("ch2"))) / 16.0).epsilon(1e-12));
    // Temperature: raw counts (472 at 25 °C nominal, −5.35 counts/°C → 445 at 30 °C).
    CHECK(f1.values[6] == 472.0);
    CHECK(f1.values[8] == 445.0);
}

TEST_CASE("scale is applied as documented", "[mpl115a][compensation]") {
    Rig rig("sensor-scale");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"scale", 1.0}, {"sensors", std::vector<std::int64_t>{3}}}), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.strip->chip(3).set_pressure_kpa(106.325);
    auto f = read_frame(s);
    REQUIRE(f.valid);
    CHECK(f.values[0] == Approx(5.0).margin(0.126));
}

TEST_CASE("the baseline is retaken at each recording's start", "[mpl115a][baseline]") {
    Rig rig("sensor-baseline");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"sensors", std::vector<std::int64_t>{0}}}), {}).ok());
    REQUIRE(s.start_recording({}).ok());
    rig.strip->chip(0).set_pressure_kpa(103.0);
    CHECK(read_frame(s).values[0] > 0.1);
    REQUIRE(s.stop_recording().ok());
    REQUIRE(s.start_recording({}).ok());  // ambient drifted: the new baseline absorbs it
    CHECK(read_frame(s).values[0] == Approx(0.0).margin(1e-12));
    auto again = s.invoke("rebaseline", {});
    REQUIRE(again.ok());
    CHECK(std::get<double>(again->at("ch1")) == Approx(103.0).margin(0.07));
}

TEST_CASE("sensors on two strips via select_addresses, named channels", "[mpl115a]") {
    Rig rig("sensor-two-strips");
    auto strip1 = std::make_shared<rollsense::hal::TakkStripModel>(rollsense::hal::TakkStripModelConfig{.strip = 1, .seed = 9});
    rig.bus->attach(strip1);
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec, {{"select_addresses", std::vector<std::int64_t>{5, 8, 9}},
                                             {"channel_names", std::vector<std::string>{"left", "mid", "right"}},
                                             {"scale", 1.0}}),
                           {})
                .ok());
    CHECK(s.channels()[1].name == "mid");
    REQUIRE(s.start_recording({}).ok());
    rig.strip->chip(5).set_pressure_kpa(102.325);
    strip1->chip(0).set_pressure_kpa(104.325);
    strip1->chip(1).set_pressure_kpa(101.325);
    auto f = read_frame(s);
    REQUIRE(f.valid);
    CHECK(f.values[0] == Approx(1.0).margin(0.126));
    CHECK(f.values[1] == Approx(3.0).margin(0.126));
    CHECK(f.values[2] == Approx(0.0).margin(0.126));
}

TEST_CASE("parameter mistakes are refused with the reason", "[mpl115a][params]") {
    Rig rig("sensor-params");
    plugins::Mpl115aSensor s;
    auto dup = s.on_configure(params(rig.spec, {{"sensors", std::vector<std::int64_t>{1, 1}}}), {});
    CHECK(dup.code() == ErrorCode::invalid_argument);
    CHECK_THAT(dup.message(), Catch::Contains("twice"));
    auto all = s.on_configure(params(rig.spec, {{"select_addresses", std::vector<std::int64_t>{6}}}), {});
    CHECK_THAT(all.message(), Catch::Contains("all-strips"));
    auto names = s.on_configure(params(rig.spec, {{"channel_names", std::vector<std::string>{"a,b", "c", "d"}}}), {});
    CHECK_THAT(names.message(), Catch::Contains("CSV"));
    auto count = s.on_configure(params(rig.spec, {{"channel_names", std::vector<std::string>{"a"}}}), {});
    CHECK_THAT(count.message(), Catch::Contains("1 names for 3 sensors"));
    // The schema itself bounds the conversion wait at the datasheet maximum.
    auto short_wait = validate_params(plugins::mpl115a_schema(), {{"conversion_time_ms", 1.0}}, "profile");
    CHECK_FALSE(short_wait.ok());
}

TEST_CASE("deactivate leaves no chip selected", "[mpl115a]") {
    Rig rig("sensor-deactivate");
    plugins::Mpl115aSensor s;
    REQUIRE(s.on_configure(params(rig.spec), {}).ok());
    REQUIRE(s.on_activate().ok());
    REQUIRE(rig.bus->quick_write(0x02).ok());  // someone left slot 2 selected
    REQUIRE(s.on_deactivate().ok());
    CHECK_FALSE(rig.strip->selected(2));
}

// On a rig: ROLLSENSE_TEST_I2C_BUS=/dev/i2c-1 test_mpl115a "[.hw]"
// (a TakkStrip at strip 0 with chips in slots 0–2, nobody touching it).
TEST_CASE("the sensor on a real TakkStrip", "[.hw][mpl115a]") {
    const char* bus = std::getenv("ROLLSENSE_TEST_I2C_BUS");
    REQUIRE(bus);
    plugins::Mpl115aSensor s;
    auto st = s.on_configure(params(bus, {{"raw_channels", true}}), {});
    INFO(st.message());
    REQUIRE(st.ok());
    REQUIRE(s.on_activate().ok());
    REQUIRE(s.start_recording({}).ok());
    for (int i = 0; i < 31; ++i) {
        auto f = read_frame(s, i / 31.1);
        INFO(f.reason);
        CHECK(f.valid);
        for (int k = 0; k < 3; ++k) {
            CHECK(std::abs(f.values[k]) < 0.05);               // untouched: a few counts of noise
            CHECK(f.values[3 + k] > 80.0);                      // room air, kPa
            CHECK(f.values[3 + k] < 110.0);
        }
    }
    REQUIRE(s.on_deactivate().ok());
}
