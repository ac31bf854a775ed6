// A sensor whose constructor throws a value that is not a std::exception: the
// registry names the plugin instead of ending the process (std::terminate).
#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

ParamSchema no_params() { return {}; }

class CtorThrower final : public Sensor {
public:
    CtorThrower() { throw 42; }
    std::vector<ChannelInfo> channels() const override { return {{"ch1", "1", "constant"}}; }
    Status read(const SampleInput&, Frame& out) override { return out.values[0] = 1.0, Status{}; }
};
}  // namespace

ROLLSENSE_PLUGIN(CtorThrower, sensor, "test_ctor_thrower", "0.0.1", "test plugin whose constructor throws 42",
                 no_params)
