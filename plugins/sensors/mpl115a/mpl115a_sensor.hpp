// The `mpl115a` sensor plugin: MPL115A2 barometers on a TakkStrip, over I2C.
//
// Configure: open the bus, check the adapter can do quick commands and
// combined transfers, make sure every configured sensor answers, read and
// decode each sensor's coefficients once.
// Each sample: select all → start conversion → deselect all → wait the
// conversion time (on the bus's clock) → per sensor: select, read Padc/Tadc,
// deselect → compensate to kPa with the datasheet formula.
// Output per sensor: (kPa − baseline kPa) · scale, the unitless reading the
// feature pipeline expects (baseline = mean of the first conversions of a
// recording; scale 1/16 per kPa by default, so one unit ≈ 16 kPa as in the
// paper's data, simulation.md §3), optionally also the raw kPa and the raw
// temperature count. A failed read leaves NaN and marks the frame invalid with
// the reason — never a silent zero.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "rollsense/hal/i2c.hpp"
#include "rollsense/hal/mpl115a.hpp"
#include "rollsense/hal/takkstrip.hpp"
#include "rollsense/hal/takkstrip_model.hpp"
#include "rollsense/sensor.hpp"

namespace rollsense::plugins {

ParamSchema mpl115a_schema();

class Mpl115aSensor final : public Sensor {
public:
    Status on_configure(const ParamSet& params, const PluginContext& context) override;
    Status on_activate() override;
    Status on_deactivate() override;
    Status on_cleanup() override;
    Status on_recover() override;
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    std::vector<ChannelInfo> channels() const override;
    Status start_recording(const SampleInput& input) override;
    Status read(const SampleInput& input, Frame& out) override;

private:
    struct Channel {
        std::string name;
        std::uint8_t select = 0;
        hal::mpl115a::Coefficients coefficients;
        double baseline_kpa = 0.0;
        bool has_baseline = false;
        // stuck-ADC detection: identical raw words in a row
        hal::mpl115a::AdcReading last{};
        int repeats = 0;
        int failed_samples = 0;  // samples in a row without a valid reading
    };
    struct Injection {
        std::size_t channel = 0;
        hal::Mpl115aFault fault = hal::Mpl115aFault::none;
        double after = 0.0;  // run-clock seconds
        bool applied = false;
    };
    struct SensorSample {
        bool ok = false;
        double kpa = 0.0;
        hal::mpl115a::AdcReading adc{};
        std::string reason;
    };

    // One sample cycle for every channel (no baseline, no stuck check).
    std::vector<SensorSample> sample_all();
    Status take_baseline();
    Status check_failing_channels(const Frame& out);
    // The chip behind a select address in a strip this sensor attached (simulate), or null.
    hal::Mpl115aChip* modelled_chip(std::uint8_t select);
    void apply_due_injections(double time);
    void release();

    mutable std::mutex mutex_;
    std::shared_ptr<hal::I2cBus> bus_;
    std::unique_ptr<hal::takkstrip::Host> host_;
    std::vector<Channel> channels_;
    std::vector<ChannelInfo> channel_info_;
    double scale_ = 0.0625;
    std::chrono::microseconds conversion_time_{3000};
    int baseline_samples_ = 4;
    int stuck_samples_ = 100;
    int retries_ = 1;
    int fault_after_ = 31;
    std::vector<std::shared_ptr<hal::TakkStripModel>> models_;  // attached by simulate = true
    std::vector<Injection> injections_;
    bool raw_channels_ = false;
};

}  // namespace rollsense::plugins
