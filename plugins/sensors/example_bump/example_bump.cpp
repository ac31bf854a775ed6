// `example_bump`: the smallest useful sensor plugin, written as a template for
// new ones (docs/writing-a-sensor-plugin.md walks through it).
//
// It models N pressure cells along a finger: each reads a Gaussian bump when
// the watched joint's angle passes the cell's angle, while a trial is clamped.
// No physics — for that see the `sim` plugin — but it reacts to what the
// script commands, through the joint states the kernel hands it.
#include <cmath>
#include <random>

#include "rollsense/plugin.hpp"

namespace {

using namespace rollsense;

// 1. Declare the parameters: name, default, documentation, range, unit.
//    The kernel checks a profile against this before on_configure runs.
ParamSchema example_bump_schema() {
    return {
        param_string("joint", std::string("sensing_finger"), "joint whose angle moves the contact"),
        param_number_list("cell_angles", std::vector<double>{-20, 0, 20}, "angle at which each cell is passed", {}, {},
                          "deg"),
        param_number("width", 6.0, "angular width (sigma) of a bump", 0.1, 90, "deg"),
        param_number("amplitude", 0.2, "peak reading", 0, {}, "1"),
        param_number("noise", 0.002, "standard deviation of white noise", 0, {}, "1"),
    };
}

// 2. Derive from the interface and fill the hooks you need.
class ExampleBump final : public Sensor {
public:
    Status on_configure(const ParamSet& p, const PluginContext&) override {
        joint_ = p.get_string("joint");
        cells_ = p.get_number_list("cell_angles");
        width_ = p.get_number("width");
        amplitude_ = p.get_number("amplitude");
        noise_ = p.get_number("noise");
        if (cells_.empty()) return {ErrorCode::invalid_argument, "cell_angles is empty"};
        return {};
    }

    std::vector<ChannelInfo> channels() const override {
        std::vector<ChannelInfo> out;
        for (std::size_t i = 0; i < cells_.size(); ++i)
            out.push_back({"ch" + std::to_string(i + 1), "1", "bump reading of cell " + std::to_string(i + 1)});
        return out;
    }

    // Same seed, same noise: trials are reproducible.
    Status begin_trial(const TrialInfo& trial) override {
        rng_.seed(trial.seed);
        return {};
    }

    Status read(const SampleInput& in, Frame& out) override {
        const JointState* j = in.joint(joint_);
        if (!j) {  // a read problem is reported in the frame, never as a silent zero
            out.valid = false;
            out.reason = "no joint '" + joint_ + "' in this profile";
            for (auto& v : out.values) v = std::nan("");
            return {};
        }
        std::normal_distribution<double> noise(0.0, noise_);
        for (std::size_t i = 0; i < cells_.size(); ++i) {
            const double d = (j->position - cells_[i]) / width_;
            out.values[i] = amplitude_ * std::exp(-0.5 * d * d) + noise(rng_);
        }
        return {};
    }

private:
    std::string joint_;
    std::vector<double> cells_;
    double width_ = 6, amplitude_ = 0.2, noise_ = 0.002;
    std::mt19937_64 rng_;
};

}  // namespace

// 3. Export the manifest: class, kind, name, version, description, schema.
ROLLSENSE_PLUGIN(ExampleBump, sensor, "example_bump", "1.0.0",
                 "Example sensor: Gaussian bumps as a joint sweeps past N cells (a template for new plugins)",
                 example_bump_schema)
