#include "rollsense/hal/dynamixel/injected_fault.hpp"

#include <cmath>
#include <cstdlib>

namespace rollsense::hal::dxl {

std::string_view to_string(FaultKind kind) {
    switch (kind) {
        case FaultKind::silent: return "silent";
        case FaultKind::hardware_error: return "hardware-error";
        case FaultKind::corrupt: return "corrupt";
        case FaultKind::slow: return "slow";
    }
    return "?";
}

Result<InjectedFault> parse_injected_fault(std::string_view spec) {
    const std::string where = "fault '" + std::string(spec) + "'";
    const auto a = spec.find(':'), b = spec.rfind(':');
    if (a == std::string_view::npos || a == b)
        return Error{ErrorCode::invalid_argument, where + ": expected ID:KIND:AFTER_S, e.g. 2:silent:1.5"};
    const std::string id_text(spec.substr(0, a)), kind(spec.substr(a + 1, b - a - 1)), after(spec.substr(b + 1));
    char* end = nullptr;
    const long id = std::strtol(id_text.c_str(), &end, 10);
    if (id_text.empty() || *end != '\0' || id < 0 || id > 252)
        return Error{ErrorCode::invalid_argument, where + ": the servo id must be an integer 0..252"};
    InjectedFault f;
    f.id = static_cast<std::uint8_t>(id);
    if (kind == "silent") f.kind = FaultKind::silent;
    else if (kind == "hardware-error") f.kind = FaultKind::hardware_error;
    else if (kind == "corrupt") f.kind = FaultKind::corrupt;
    else if (kind == "slow") f.kind = FaultKind::slow;
    else
        return Error{ErrorCode::invalid_argument,
                     where + ": unknown kind '" + kind + "' (silent, hardware-error, corrupt or slow)"};
    end = nullptr;
    f.after_s = std::strtod(after.c_str(), &end);
    if (after.empty() || *end != '\0' || !std::isfinite(f.after_s) || f.after_s < 0 || f.after_s > 1e6)
        return Error{ErrorCode::invalid_argument, where + ": AFTER_S must be seconds, 0..1e6"};
    return f;
}

}  // namespace rollsense::hal::dxl
