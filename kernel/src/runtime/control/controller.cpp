#include "runtime/control/controller.hpp"

namespace rollsense::runtime {
namespace {
std::vector<ControllerType>& types() {
    static std::vector<ControllerType> list;
    return list;
}
}  // namespace

ControllerRegistration::ControllerRegistration(ControllerType type) { types().push_back(std::move(type)); }

const ControllerType* find_controller_type(const std::string& name) {
    for (const auto& t : types())
        if (t.name == name) return &t;
    return nullptr;
}

std::vector<std::string> controller_type_names() {
    std::vector<std::string> out;
    for (const auto& t : types()) out.push_back(t.name);
    return out;
}

}  // namespace rollsense::runtime
