// A modelled TakkStrip on a fresh fake bus, and parameter sets for the plugin.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <string>

#include "mpl115a_sensor.hpp"
#include "rollsense/hal/fake_i2c_bus.hpp"
#include "rollsense/hal/takkstrip_model.hpp"

namespace mpl115a_test {

struct Rig {
    std::string spec;
    std::shared_ptr<rollsense::hal::FakeI2cBus> bus;
    std::shared_ptr<rollsense::hal::TakkStripModel> strip;

    explicit Rig(const std::string& name, rollsense::hal::TakkStripModelConfig cfg = {})
        : spec("fake:" + name), bus(rollsense::hal::FakeI2cBus::get(name)) {
        bus->reset();
        strip = std::make_shared<rollsense::hal::TakkStripModel>(cfg);
        bus->attach(strip);
    }
};

inline rollsense::ParamSet params(const std::string& bus, rollsense::ValueMap extra = {}) {
    extra["bus"] = bus;
    auto r = rollsense::validate_params(rollsense::plugins::mpl115a_schema(), extra, "test profile: devices.tactile");
    INFO((r.ok() ? std::string() : r.error().message));
    REQUIRE(r.ok());
    return r.value();
}

inline rollsense::Frame read_frame(rollsense::Sensor& s, double t = 0.0) {
    rollsense::SampleInput in;
    in.time = t;
    rollsense::Frame f;
    f.time = t;
    f.values.assign(s.channels().size(), 0.0);
    auto st = s.read(in, f);
    INFO(st.message());
    REQUIRE(st.ok());
    return f;
}

}  // namespace mpl115a_test
