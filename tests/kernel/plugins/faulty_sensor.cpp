// A sensor with the faults a careless plugin has: channel names it chooses
// (parameter `names`, so a test can repeat one) and a channel that reads NaN in
// a frame it reports valid (`nan_channel`), for the kernel's checks of both.
#include <cmath>
#include <sstream>

#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

ParamSchema faulty_schema() {
    return {param_string("names", std::string("a,b,c"), "the channel names, comma-separated", {}),
            param_int("nan_channel", std::int64_t{-1}, "channel that reads NaN in a valid frame (-1: none)", -1, 15)};
}

class FaultySensor final : public Sensor {
public:
    Status on_configure(const ParamSet& p, const PluginContext&) override {
        std::istringstream names(p.get_string("names"));
        for (std::string name; std::getline(names, name, ',');) channels_.push_back({name, "1", "test channel"});
        nan_channel_ = p.get_int("nan_channel");
        return {};
    }
    std::vector<ChannelInfo> channels() const override { return channels_; }
    Status read(const SampleInput&, Frame& out) override {
        for (std::size_t c = 0; c < out.values.size(); ++c)
            out.values[c] = static_cast<std::int64_t>(c) == nan_channel_ ? std::nan("") : 1.0 + static_cast<double>(c);
        return {};  // out.valid stays true: the fault under test
    }

private:
    std::vector<ChannelInfo> channels_;
    std::int64_t nan_channel_ = -1;
};
}  // namespace

ROLLSENSE_PLUGIN(FaultySensor, sensor, "test_faulty_sensor", "0.0.1", "test plugin with faulty channels",
                 faulty_schema)
