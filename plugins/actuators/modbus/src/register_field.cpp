#include "register_field.hpp"

#include <cmath>

namespace rollsense::modbus {

const std::vector<std::string>& format_names() {
    static const std::vector<std::string> names{"u16", "s16", "u32", "s32", "u32_swapped", "s32_swapped",
                                                "u8_high", "u8_low"};
    return names;
}

Result<Format> parse_format(const std::string& name) {
    const auto& n = format_names();
    for (std::size_t i = 0; i < n.size(); ++i)
        if (n[i] == name) return static_cast<Format>(i);
    return Error{ErrorCode::invalid_argument, "unknown register format '" + name +
                                                  "' (u16, s16, u32, s32, u32_swapped, s32_swapped, u8_high, u8_low)"};
}

int register_count(Format f) {
    switch (f) {
        case Format::u32:
        case Format::s32:
        case Format::u32_swapped:
        case Format::s32_swapped: return 2;
        default: return 1;
    }
}

std::int64_t raw_min(Format f) {
    switch (f) {
        case Format::s16: return INT16_MIN;
        case Format::s32:
        case Format::s32_swapped: return INT32_MIN;
        default: return 0;
    }
}

std::int64_t raw_max(Format f) {
    switch (f) {
        case Format::u16: return UINT16_MAX;
        case Format::s16: return INT16_MAX;
        case Format::u32:
        case Format::u32_swapped: return UINT32_MAX;
        case Format::s32:
        case Format::s32_swapped: return INT32_MAX;
        case Format::u8_high:
        case Format::u8_low: return UINT8_MAX;
    }
    return 0;
}

std::int64_t RegisterField::decode_raw(std::span<const std::uint16_t> block, int block_start) const {
    const auto i = static_cast<std::size_t>(address - block_start);
    const std::uint16_t r0 = block[i];
    switch (format) {
        case Format::u16: return r0;
        case Format::s16: return static_cast<std::int16_t>(r0);
        case Format::u8_high: return r0 >> 8;
        case Format::u8_low: return r0 & 0xFF;
        case Format::u32: return (std::uint32_t{r0} << 16) | block[i + 1];
        case Format::s32: return static_cast<std::int32_t>((std::uint32_t{r0} << 16) | block[i + 1]);
        case Format::u32_swapped: return (std::uint32_t{block[i + 1]} << 16) | r0;
        case Format::s32_swapped: return static_cast<std::int32_t>((std::uint32_t{block[i + 1]} << 16) | r0);
    }
    return 0;
}

void RegisterField::encode_raw(std::int64_t raw, std::span<std::uint16_t> block, int block_start) const {
    const auto i = static_cast<std::size_t>(address - block_start);
    const auto u = static_cast<std::uint32_t>(raw);
    switch (format) {
        case Format::u16:
        case Format::s16: block[i] = static_cast<std::uint16_t>(u); break;
        case Format::u8_high: block[i] = static_cast<std::uint16_t>((block[i] & 0x00FF) | ((u & 0xFF) << 8)); break;
        case Format::u8_low: block[i] = static_cast<std::uint16_t>((block[i] & 0xFF00) | (u & 0xFF)); break;
        case Format::u32:
        case Format::s32:
            block[i] = static_cast<std::uint16_t>(u >> 16);
            block[i + 1] = static_cast<std::uint16_t>(u & 0xFFFF);
            break;
        case Format::u32_swapped:
        case Format::s32_swapped:
            block[i] = static_cast<std::uint16_t>(u & 0xFFFF);
            block[i + 1] = static_cast<std::uint16_t>(u >> 16);
            break;
    }
}

std::optional<std::int64_t> RegisterField::to_raw(double value) const {
    if (scale == 0.0) return std::nullopt;
    const double raw = std::round((value - offset) / scale);
    if (!std::isfinite(raw) || raw < static_cast<double>(raw_min(format)) || raw > static_cast<double>(raw_max(format)))
        return std::nullopt;
    return static_cast<std::int64_t>(raw);
}

}  // namespace rollsense::modbus
