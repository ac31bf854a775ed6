// Must NOT compile: a sensor class declared as a classifier plugin. Before the
// check in ROLLSENSE_PLUGIN it compiled, was listed as a classifier, and failed
// only when used ("factory returned nothing"). Built by the ctest
// plugin_of_another_kind_does_not_compile, never by `all`.
#include "rollsense/plugin.hpp"

namespace {
class OnlyASensor : public rollsense::Sensor {
public:
    std::vector<rollsense::ChannelInfo> channels() const override { return {}; }
    rollsense::Status read(const rollsense::SampleInput&, rollsense::Frame&) override { return {}; }
};
rollsense::ParamSchema schema() { return {}; }
}  // namespace

ROLLSENSE_PLUGIN(OnlyASensor, classifier, "kind_mismatch", "0.1", "a sensor declared as a classifier", schema)
