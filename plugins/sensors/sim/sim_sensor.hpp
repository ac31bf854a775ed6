// The `sim` tactile sensor: three simulated MPL115A barometers under the rubber
// of the sensing finger, reacting to the finger angle and clamping current the
// kernel hands over with every sample (the simulation follows what the script
// commanded: roll half-way, at another speed, backwards — the data follow).
#pragma once

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rollsense/object_catalogue.hpp"
#include "rollsense/sensor.hpp"
#include "sim_model.hpp"
#include "sim_schema.hpp"

namespace rollsense::sim {

class SimSensor : public Sensor {
public:
    Status on_configure(const ParamSet& params, const PluginContext& context) override;
    Status on_cleanup() override;
    Status on_recover() override;
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    std::vector<ChannelInfo> channels() const override;
    Status begin_trial(const TrialInfo& trial) override;
    Status start_recording(const SampleInput& input) override;
    Status read(const SampleInput& input, Frame& out) override;
    Status stop_recording() override;
    Status end_trial() override;

    const ObjectCatalogue* catalogue() const { return catalogue_ ? &*catalogue_ : nullptr; }

private:
    // Finger angle (rad) and clamping current (mA) from a sample, or an error
    // naming the missing joint.
    Result<double> finger_angle(const SampleInput& input) const;
    double clamp_current(const SampleInput& input);

    SimSettings settings_;
    PluginContext context_;
    std::optional<ObjectCatalogue> catalogue_;
    DeviceState device_;
    std::unique_ptr<TrialModel> trial_;
    TrialInfo trial_info_;
    const ObjectSpec* object_ = nullptr;
    bool warned_no_pushing_joint_ = false;
    double last_palm_width_ = 0.0;
    bool have_palm_width_ = false;
};

}  // namespace rollsense::sim
