// A plugin whose global object's constructor throws while the loader opens it:
// the exception unwinds out of dlopen and leaves the loader's lock held, so the
// process must stop with the file named rather than go on and hang (it did).
#include "rollsense/plugin.hpp"

#include <stdexcept>

namespace {
using namespace rollsense;

ParamSchema no_params() { return {}; }

struct ThrowsWhileLoading {
    ThrowsWhileLoading() { throw std::runtime_error("static initialisation failed"); }
} const throws_while_loading;

class NeverMade final : public Sensor {
public:
    std::vector<ChannelInfo> channels() const override { return {{"ch1", "1", "constant"}}; }
    Status read(const SampleInput&, Frame& out) override { return out.values[0] = 1.0, Status{}; }
};
}  // namespace

ROLLSENSE_PLUGIN(NeverMade, sensor, "test_static_thrower", "0.0.1", "test plugin whose static initialiser throws",
                 no_params)
