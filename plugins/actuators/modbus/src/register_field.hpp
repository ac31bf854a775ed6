// One value inside a block of 16-bit Modbus registers: where it is, how its
// bytes are packed, and how raw counts scale to physical units.
//
// Formats (Modbus registers are big-endian 16-bit words):
//   u16, s16               one register
//   u32, s32               two registers, high word first (the usual order)
//   u32_swapped, s32_swapped  two registers, low word first
//   u8_high, u8_low        one byte of a register (Robotiq-style byte maps:
//                          byte 2k is the high half of register k)
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::modbus {

enum class Format { u16, s16, u32, s32, u32_swapped, s32_swapped, u8_high, u8_low };

Result<Format> parse_format(const std::string& name);
const std::vector<std::string>& format_names();
int register_count(Format f);  // 1 or 2
std::int64_t raw_min(Format f);
std::int64_t raw_max(Format f);

struct RegisterField {
    int address = -1;  // -1 = not mapped
    Format format = Format::u16;
    double scale = 1.0;   // physical units per raw count
    double offset = 0.0;  // physical value at raw 0

    bool mapped() const { return address >= 0; }
    int last_address() const { return address + register_count(format) - 1; }

    // Raw integer from a block of registers that starts at `block_start`.
    std::int64_t decode_raw(std::span<const std::uint16_t> block, int block_start) const;
    double decode(std::span<const std::uint16_t> block, int block_start) const {
        return static_cast<double>(decode_raw(block, block_start)) * scale + offset;
    }
    // Write a raw value into the block, leaving the other byte of a shared register alone.
    void encode_raw(std::int64_t raw, std::span<std::uint16_t> block, int block_start) const;
    // Physical value -> raw count; nullopt when it does not fit the format.
    std::optional<std::int64_t> to_raw(double value) const;
};

}  // namespace rollsense::modbus
