// The TakkStrip device model and the host protocol against it: ATtiny
// select/deselect on the address byte, per-chip register files, conversion
// timing, pressure driving, faults, discovery.
#include <catch2/catch.hpp>

#include <cmath>

#include "rollsense/hal/fake_i2c_bus.hpp"
#include "rollsense/hal/takkstrip.hpp"
#include "rollsense/hal/takkstrip_model.hpp"

using namespace rollsense;
using namespace rollsense::hal;
namespace ms = rollsense::hal::mpl115a;
namespace ts = rollsense::hal::takkstrip;

namespace {

struct Rig {
    std::shared_ptr<FakeI2cBus> bus;
    std::shared_ptr<TakkStripModel> strip;
    ts::Host host;
    Rig(const std::string& name, TakkStripModelConfig cfg = {})
        : bus(FakeI2cBus::get(name)), strip(std::make_shared<TakkStripModel>(cfg)), host(bus) {
        bus->reset();
        bus->attach(strip);
    }
};

}  // namespace

TEST_CASE("the ATtiny selects and deselects on the address byte alone", "[takkstrip][model]") {
    Rig rig("attiny", {.strip = 1, .sensors = 5});
    auto& bus = *rig.bus;
    auto& strip = *rig.strip;

    REQUIRE(bus.quick_write(0x0a).ok());  // strip 1 slot 2
    CHECK(strip.selected(2));
    CHECK_FALSE(strip.selected(1));
    REQUIRE(bus.quick_write(0x0b).ok());  // selecting slot 3 releases slot 2
    CHECK(strip.selected(3));
    CHECK_FALSE(strip.selected(2));
    REQUIRE(bus.quick_read(0x0b).ok());  // a read deselects
    CHECK_FALSE(strip.selected(3));

    // A 1-byte read deselects too.
    REQUIRE(bus.quick_write(0x08).ok());
    std::array<std::uint8_t, 1> one{};
    REQUIRE(bus.read(0x08, one).ok());
    CHECK_FALSE(strip.selected(0));

    // 0x06: write = select all, read = deselect all.
    REQUIRE(bus.quick_write(ts::kAllStrips).ok());
    for (int s = 0; s < 5; ++s) CHECK(strip.selected(s));
    REQUIRE(bus.quick_read(ts::kAllStrips).ok());
    for (int s = 0; s < 5; ++s) CHECK_FALSE(strip.selected(s));

    // Slots beyond the strip's chips, and other strips' addresses, are not acknowledged.
    CHECK(bus.quick_write(0x0d).code() == ErrorCode::hardware_fault);
    CHECK(bus.quick_write(0x02).code() == ErrorCode::hardware_fault);
}

TEST_CASE("a chip answers at 0x60 only while selected", "[takkstrip][model]") {
    Rig rig("only-selected");
    std::array<std::uint8_t, 8> raw{};
    const std::uint8_t pointer[1] = {ms::kRegCoefficients};
    auto s = rig.bus->write_read(ms::kAddress, pointer, raw);
    REQUIRE_FALSE(s.ok());
    CHECK(s.code() == ErrorCode::hardware_fault);
    CHECK_THAT(s.message(), Catch::Contains("0x60"));

    auto c = rig.host.read_coefficients(ts::select_address(0, 3));
    REQUIRE(c.ok());
    CHECK(c->words.a0 == rig.strip->chip(3).coefficients().words.a0);
    CHECK(c->words.c12 == rig.strip->chip(3).coefficients().words.c12);
    CHECK(c->c12 == rig.strip->chip(3).coefficients().c12);
    CHECK_FALSE(rig.strip->selected(3));  // the host deselected it again
}

TEST_CASE("modelled chips have distinct, plausible coefficients", "[takkstrip][model]") {
    Rig rig("plausible");
    for (int slot = 0; slot < rig.strip->sensor_count(); ++slot) {
        const auto& c = rig.strip->chip(slot).coefficients();
        CHECK((c.words.c12 & 0x3) == 0);
        CHECK(c.a0 == Approx(2009.75).margin(60.0));
        CHECK(c.b1 < 0);
        CHECK(c.b2 < 0);
        CHECK(c.c12 > 0);
        if (slot > 0) CHECK(c.words.a0 != rig.strip->chip(slot - 1).coefficients().words.a0);
    }
}

TEST_CASE("two chips selected at once garble a read (wired-AND)", "[takkstrip][model]") {
    Rig rig("contention");
    REQUIRE(rig.bus->quick_write(ts::kAllStrips).ok());
    std::array<std::uint8_t, 8> raw{};
    const std::uint8_t pointer[1] = {ms::kRegCoefficients};
    REQUIRE(rig.bus->write_read(ms::kAddress, pointer, raw).ok());
    CHECK(rig.strip->contended_reads() == 1);
    auto expected = ms::encode_coefficients(rig.strip->chip(0).coefficients().words);
    for (int slot = 1; slot < rig.strip->sensor_count(); ++slot) {
        auto b = ms::encode_coefficients(rig.strip->chip(slot).coefficients().words);
        for (std::size_t i = 0; i < 8; ++i) expected[i] &= b[i];
    }
    CHECK(raw == expected);
}

TEST_CASE("a conversion takes its time on the bus clock, early reads see the old result", "[takkstrip][model]") {
    Rig rig("conversion", {.conversion_time = 3e-3});
    auto& chip = rig.strip->chip(0);
    const auto before = chip.last_result();
    chip.set_pressure_kpa(108.0);
    REQUIRE(rig.host.start_conversion_all().ok());
    CHECK(chip.conversions_started() == 1);
    CHECK(rig.strip->chip(5).conversions_started() == 1);  // every chip converted at once

    // Straight away: still converting, registers hold the previous result.
    auto early = rig.host.read_adc(ts::select_address(0, 0));
    REQUIRE(early.ok());
    CHECK(early->padc == before.padc);
    CHECK(chip.early_reads() == 1);

    rig.bus->sleep_for(ms::kConversionTimeMax);
    auto late = rig.host.read_adc(ts::select_address(0, 0));
    REQUIRE(late.ok());
    CHECK(late->padc != before.padc);
    CHECK(chip.early_reads() == 1);
    CHECK(ms::pressure_kpa(chip.coefficients(), *late) == Approx(108.0).margin(0.07));  // half a count
}

TEST_CASE("the modelled ADC values compensate back to the driven pressure", "[takkstrip][model]") {
    Rig rig("driven");
    for (double kpa : {60.0, 85.5, 101.325, 104.2, 109.0}) {
        for (int slot = 0; slot < 6; ++slot) rig.strip->chip(slot).set_pressure_kpa(kpa + slot);
        REQUIRE(rig.host.start_conversion_all().ok());
        rig.bus->sleep_for(ms::kConversionTimeMax);
        for (int slot = 0; slot < 6; ++slot) {
            auto r = rig.host.read_adc(ts::select_address(0, slot));
            REQUIRE(r.ok());
            const double got = ms::pressure_kpa(rig.strip->chip(slot).coefficients(), *r);
            INFO("slot " << slot << " at " << kpa + slot << " kPa");
            // One Padc count is ≈ 0.126 kPa for these coefficients; rounding is half of it.
            CHECK(got == Approx(kpa + slot).margin(0.07));
        }
    }
    // Far beyond the range the ADC rails (Padc falls with pressure: 0 counts).
    rig.strip->chip(0).set_pressure_kpa(300.0);
    REQUIRE(rig.host.start_conversion_all().ok());
    rig.bus->sleep_for(ms::kConversionTimeMax);
    auto railed = rig.host.read_adc(ts::select_address(0, 0));
    REQUIRE(railed.ok());
    CHECK(railed->padc == 0);
    // A pressure source is sampled at the start of each conversion (bus time).
    rig.strip->chip(0).set_pressure_source([](double t) { return 100.0 + 1000.0 * t; });
    const double t_start = rig.bus->now();
    REQUIRE(rig.host.start_conversion_all().ok());
    rig.bus->sleep_for(ms::kConversionTimeMax);
    auto r = rig.host.read_adc(ts::select_address(0, 0));
    REQUIRE(r.ok());
    CHECK(ms::pressure_kpa(rig.strip->chip(0).coefficients(), *r) ==
          Approx(100.0 + 1000.0 * t_start).margin(0.2));
}

TEST_CASE("injected faults: missing slot, dead chip, stuck ADC", "[takkstrip][model][faults]") {
    Rig rig("faults");
    rig.strip->set_slot_missing(1, true);
    rig.strip->chip(2).set_fault(Mpl115aFault::nack);
    rig.strip->chip(3).set_fault(Mpl115aFault::stuck);

    auto missing = rig.host.read_adc(ts::select_address(0, 1));
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().code == ErrorCode::hardware_fault);
    CHECK_THAT(missing.error().message, Catch::Contains("selecting strip 0 slot 1 (select 0x01)"));

    auto dead = rig.host.read_adc(ts::select_address(0, 2));
    REQUIRE_FALSE(dead.ok());
    CHECK_THAT(dead.error().message, Catch::Contains("slot 2") && Catch::Contains("0x60") && Catch::Contains("NACK"));
    CHECK_FALSE(rig.strip->selected(2));  // deselected despite the failure

    auto before = rig.host.read_adc(ts::select_address(0, 3));
    REQUIRE(before.ok());
    rig.strip->chip(3).set_pressure_kpa(110.0);
    REQUIRE(rig.host.start_conversion_all().ok());
    rig.bus->sleep_for(ms::kConversionTimeMax);
    auto after = rig.host.read_adc(ts::select_address(0, 3));
    REQUIRE(after.ok());
    CHECK(after->padc == before->padc);  // stuck
    CHECK(after->tadc == before->tadc);
}

TEST_CASE("discovery lists the slots that answer, with their coefficients and a reading", "[takkstrip][probe]") {
    auto bus = FakeI2cBus::get("probe");
    bus->reset();
    auto strip0 = std::make_shared<TakkStripModel>(TakkStripModelConfig{.strip = 0, .sensors = 6});
    auto strip1 = std::make_shared<TakkStripModel>(TakkStripModelConfig{.strip = 1, .sensors = 5, .seed = 7});
    bus->attach(strip0);
    bus->attach(strip1);
    strip0->set_slot_missing(3, true);
    strip0->chip(4).set_fault(Mpl115aFault::nack);
    ts::Host host(bus);
    auto report = ts::probe_strips(host, {0, 1, 2});
    REQUIRE(report.ok());
    CHECK(report->all_strips_address_acked);
    std::vector<int> found;
    for (const auto& p : report->sensors) found.push_back(p.select_address);
    CHECK(found == std::vector<int>{0x00, 0x01, 0x02, 0x04, 0x05, 0x08, 0x09, 0x0a, 0x0b, 0x0c});
    for (const auto& p : report->sensors) {
        INFO("select " << int(p.select_address));
        if (p.select_address == 0x04) {
            CHECK(p.chip.code() == ErrorCode::hardware_fault);
            CHECK_FALSE(p.coefficients);
            continue;
        }
        REQUIRE(p.chip.ok());
        REQUIRE(p.coefficients);
        auto& model = p.strip == 0 ? *strip0 : *strip1;
        CHECK(p.coefficients->words.b1 == model.chip(p.slot).coefficients().words.b1);
        REQUIRE(p.reading);
        CHECK(ms::pressure_kpa(*p.coefficients, *p.reading) == Approx(101.325).margin(0.07));
    }
    for (int s = 0; s < 6; ++s) CHECK_FALSE(strip0->selected(s));

    auto bad = ts::probe_strips(host, {12});
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().code == ErrorCode::invalid_argument);
}
