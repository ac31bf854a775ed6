// A sensor that throws where a test tells it to (parameter `throw_in`), to
// check that a plugin's exception becomes a typed error naming it, never a crash.
#include <stdexcept>

#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

ParamSchema thrower_schema() {
    return {param_string("throw_in", std::string("none"), "hook that throws",
                         {"none", "configure", "activate", "deactivate", "read", "recover", "invoke", "channels"})};
}

class Thrower final : public Sensor {
public:
    Status on_configure(const ParamSet& p, const PluginContext&) override {
        where_ = p.get_string("throw_in");
        if (where_ == "configure") throw std::runtime_error("boom in configure");
        return {};
    }
    Status on_activate() override {
        if (where_ == "activate") throw std::runtime_error("boom in activate");
        return {};
    }
    Status on_deactivate() override {
        if (where_ == "deactivate") throw std::runtime_error("boom in deactivate");
        return {};
    }
    Status on_recover() override {
        if (where_ == "recover") throw std::logic_error("boom in recover");
        where_ = "none";  // recovering clears the fault
        return {};
    }
    std::vector<ChannelInfo> channels() const override {
        if (where_ == "channels") throw std::runtime_error("boom in channels");
        return {{"ch1", "1", "constant"}};
    }
    Status read(const SampleInput&, Frame& out) override {
        if (where_ == "read") throw std::runtime_error("boom in read");
        out.values[0] = 1.0;
        return {};
    }
    Result<ValueMap> invoke(const std::string& verb, const ValueMap&) override {
        if (where_ == "invoke") throw 42;  // not even a std::exception
        if (verb == "echo") return ValueMap{{"ok", ParamValue{true}}};
        return Error{ErrorCode::unsupported, "no operation '" + verb + "'"};
    }

private:
    std::string where_;
};
}  // namespace

ROLLSENSE_PLUGIN(Thrower, sensor, "test_thrower", "0.0.1", "test plugin that throws on demand", thrower_schema)
