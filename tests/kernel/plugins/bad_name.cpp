// A plugin whose name has a dash: a model file spells a classifier's '_' as '-', so predict looked for 'dash_name'
// and found nothing (review). The loader refuses the name, saying which characters a name may hold.
#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

ParamSchema no_params() { return {}; }

class DashName final : public Sensor {
public:
    std::vector<ChannelInfo> channels() const override { return {{"ch1", "1", "constant"}}; }
    Status read(const SampleInput&, Frame& out) override { return out.values[0] = 1.0, Status{}; }
};
}  // namespace

ROLLSENSE_PLUGIN(DashName, sensor, "dash-name", "0.0.1", "test plugin whose name is not a-z, 0-9 and _", no_params)
