#include "rollsense/hal/dynamixel/emulator_config.hpp"

#include <charconv>
#include <string>

namespace rollsense::hal::dxl {
namespace {

std::vector<std::string_view> split(std::string_view s, char sep) {
    std::vector<std::string_view> out;
    std::size_t start = 0;
    for (;;) {
        const auto at = s.find(sep, start);
        out.push_back(s.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
        if (at == std::string_view::npos) return out;
        start = at + 1;
    }
}

bool parse_double(std::string_view s, double& out) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

Result<OperatingMode> parse_operating_mode(std::string_view name) {
    if (name == "position") return OperatingMode::position;
    if (name == "extended_position") return OperatingMode::extended_position;
    if (name == "current") return OperatingMode::current;
    if (name == "current_based_position") return OperatingMode::current_based_position;
    if (name == "velocity") return OperatingMode::velocity;
    return Error{ErrorCode::invalid_argument,
                 "unknown operating mode '" + std::string(name) +
                     "' (use position, extended_position, current, current_based_position or velocity)"};
}

Result<ServoSetup> parse_servo_spec(std::string_view spec) {
    const auto parts = split(spec, ':');
    const std::string usage = " in servo spec '" + std::string(spec) +
                              "' (expected ID:MODEL[:START_DEG[:MODE[:CONTACT_DEG]]], e.g. 1:XM430-W350:0)";
    if (parts.size() < 2 || parts.size() > 5) return Error{ErrorCode::invalid_argument, "wrong field count" + usage};
    ServoSetup s;
    unsigned id = 0;
    const auto r = std::from_chars(parts[0].data(), parts[0].data() + parts[0].size(), id);
    if (r.ec != std::errc() || r.ptr != parts[0].data() + parts[0].size() || id > kMaxId)
        return Error{ErrorCode::invalid_argument, "bad id '" + std::string(parts[0]) + "' (0-252)" + usage};
    s.id = static_cast<std::uint8_t>(id);
    s.model = find_model(parts[1]);
    if (!s.model) return Error{ErrorCode::invalid_argument, "unknown model '" + std::string(parts[1]) +
                                                                "' (known: XM430-W350, XL330-M288)" + usage};
    if (parts.size() > 2 && !parse_double(parts[2], s.start_degrees))
        return Error{ErrorCode::invalid_argument, "bad start angle '" + std::string(parts[2]) + "'" + usage};
    if (parts.size() > 3 && !parts[3].empty()) {
        auto m = parse_operating_mode(parts[3]);
        if (!m.ok()) return Error{m.error().code, m.error().message + usage};
        s.mode = *m;
    }
    if (parts.size() > 4) {
        double c = 0;
        if (!parse_double(parts[4], c))
            return Error{ErrorCode::invalid_argument, "bad contact angle '" + std::string(parts[4]) + "'" + usage};
        s.contact_degrees = c;
    }
    return s;
}

std::vector<ServoSetup> etroll_servos() {
    const ModelInfo* xm = find_model("XM430-W350");
    const ModelInfo* xl = find_model("XL330-M288");
    std::vector<ServoSetup> out(4);
    out[0] = {1, xm, 0.0, OperatingMode::position, std::nullopt, 1};
    out[1] = {2, xm, 0.0, OperatingMode::position, std::nullopt, 1};
    out[2] = {3, xm, 0.0, OperatingMode::position, std::nullopt, 1};
    out[3] = {4, xl, 0.0, OperatingMode::extended_position, std::nullopt, 1};
    return out;
}

}  // namespace rollsense::hal::dxl
