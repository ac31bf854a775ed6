// A sensor plugin whose schema contradicts itself, which loading does not
// catch: built twice, once with a default its own range refuses (used
// silently, while the same value in a profile is refused), with a parameter
// declared twice (-DDECLARED_TWICE), with a range min > max (-DEMPTY_RANGE) and
// with a name --set cannot spell (-DBAD_NAME). `rollsense plugins --check`
// must fail on each.
#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

class QuietSensor : public Sensor {
public:
    std::vector<ChannelInfo> channels() const override { return {{"a", "1", "a channel"}}; }
    Status read(const SampleInput&, Frame& out) override {
        out.values.assign(1, 0.0);
        return {};
    }
};

ParamSchema schema() {
#if defined(DECLARED_TWICE)
    return {param_number("gain", 0.5, "a gain", 0, 1), param_number("gain", 0.5, "the gain again", 0, 1)};
#elif defined(EMPTY_RANGE)
    return {param_number("gain", {}, "a gain no value can have", 10, 0)};
#elif defined(BAD_NAME)
    return {param_number("the gain", 0.5, "a name --set cannot spell", 0, 1)};
#else
    return {param_number("gain", 5.0, "a gain whose default is outside its range", 0, 1)};
#endif
}
}  // namespace

ROLLSENSE_PLUGIN(QuietSensor, sensor, "bad_schema", "0.1", "a schema that contradicts itself", schema)
