// A sensor that calls a function no library defines (a plugin built against a
// newer SDK, or linked without a library it needs): the registry must refuse
// the file when it loads it, not let the process die at the first call.
#include "rollsense/plugin.hpp"

extern "C" double rollsense_test_defined_nowhere();

namespace {
using namespace rollsense;

ParamSchema no_params() { return {}; }

class Undefined final : public Sensor {
public:
    std::vector<ChannelInfo> channels() const override { return {{"ch1", "1", "constant"}}; }
    Status read(const SampleInput&, Frame& out) override { return out.values[0] = rollsense_test_defined_nowhere(), Status{}; }
};
}  // namespace

ROLLSENSE_PLUGIN(Undefined, sensor, "test_undefined", "0.0.1", "test plugin with an undefined symbol", no_params)
