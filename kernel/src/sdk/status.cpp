#include "rollsense/status.hpp"

#include "rollsense/component.hpp"
#include "rollsense/plugin.hpp"
#include "rollsense/types.hpp"

namespace rollsense {

std::string_view to_string(ErrorCode code) noexcept {
    switch (code) {
        case ErrorCode::ok: return "ok";
        case ErrorCode::invalid_argument: return "invalid argument";
        case ErrorCode::not_found: return "not found";
        case ErrorCode::io_error: return "I/O error";
        case ErrorCode::timeout: return "timeout";
        case ErrorCode::protocol_error: return "protocol error";
        case ErrorCode::hardware_fault: return "hardware fault";
        case ErrorCode::limit_violation: return "limit violation";
        case ErrorCode::state_error: return "state error";
        case ErrorCode::plugin_error: return "plugin error";
        case ErrorCode::cancelled: return "cancelled";
        case ErrorCode::parse_error: return "parse error";
        case ErrorCode::unsupported: return "unsupported";
        case ErrorCode::script_error: return "script error";
        case ErrorCode::bad_setting: return "bad setting";
        case ErrorCode::bad_profile: return "bad profile";
    }
    return "unknown error";
}

std::string Error::describe() const { return std::string(to_string(code)) + ": " + message; }

Status Status::with_context(std::string_view context) && {
    if (!ok()) error_.message = std::string(context) + ": " + error_.message;
    return std::move(*this);
}

std::string_view to_string(LifecycleState state) noexcept {  // in the enum's order (component.hpp)
    constexpr std::string_view names[] = {"unconfigured", "inactive", "active", "error"};
    return static_cast<std::size_t>(state) < std::size(names) ? names[static_cast<std::size_t>(state)] : "?";
}

std::string_view to_string(ControlMode mode) noexcept {
    switch (mode) {
        case ControlMode::position: return "position";
        case ControlMode::extended_position: return "extended_position";
        case ControlMode::velocity: return "velocity";
        case ControlMode::current: return "current";
        case ControlMode::current_based_position: return "current_based_position";
    }
    return "?";
}

std::string_view to_string(PluginKind kind) noexcept {
    switch (kind) {
        case PluginKind::sensor: return "sensor";
        case PluginKind::actuator: return "actuator";
        case PluginKind::classifier: return "classifier";
    }
    return "unknown";
}

}  // namespace rollsense
