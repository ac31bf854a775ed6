#include "rollsense/hal/dynamixel/protocol.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

namespace rollsense::hal::dxl {
namespace {

constexpr std::array<std::uint8_t, 4> kHeader{0xFF, 0xFF, 0xFD, 0x00};

constexpr std::array<std::uint16_t, 256> make_crc_table() {
    std::array<std::uint16_t, 256> table{};
    for (unsigned i = 0; i < 256; ++i) {
        std::uint16_t c = static_cast<std::uint16_t>(i << 8);
        for (int b = 0; b < 8; ++b) c = static_cast<std::uint16_t>((c & 0x8000) ? (c << 1) ^ 0x8005 : (c << 1));
        table[i] = c;
    }
    return table;
}
constexpr auto kCrcTable = make_crc_table();

Bytes build(std::uint8_t id, std::span<const std::uint8_t> payload) {
    const Bytes stuffed = stuff(payload);
    Bytes out(kHeader.begin(), kHeader.end());
    out.push_back(id);
    put_u16(out, static_cast<std::uint16_t>(stuffed.size() + 2));  // + CRC
    out.insert(out.end(), stuffed.begin(), stuffed.end());
    put_u16(out, crc16(out));
    return out;
}

}  // namespace

std::string to_string(Instruction inst) {
    switch (inst) {
        case Instruction::ping: return "PING";
        case Instruction::read: return "READ";
        case Instruction::write: return "WRITE";
        case Instruction::reg_write: return "REG_WRITE";
        case Instruction::action: return "ACTION";
        case Instruction::factory_reset: return "FACTORY_RESET";
        case Instruction::reboot: return "REBOOT";
        case Instruction::clear: return "CLEAR";
        case Instruction::status: return "STATUS";
        case Instruction::sync_read: return "SYNC_READ";
        case Instruction::sync_write: return "SYNC_WRITE";
        case Instruction::fast_sync_read: return "FAST_SYNC_READ";
        case Instruction::bulk_read: return "BULK_READ";
        case Instruction::bulk_write: return "BULK_WRITE";
        case Instruction::fast_bulk_read: return "FAST_BULK_READ";
    }
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(inst));
    return buf;
}

std::string describe_status_error(std::uint8_t err_byte) {
    std::string text;
    switch (static_cast<StatusError>(err_byte & 0x7F)) {
        case StatusError::none: break;
        case StatusError::result_fail: text = "result fail (the servo could not process the instruction)"; break;
        case StatusError::instruction: text = "instruction error (undefined instruction, or ACTION without REG_WRITE)"; break;
        case StatusError::crc: text = "CRC error (the servo received a corrupted packet)"; break;
        case StatusError::data_range: text = "data range error (the value is outside the item's range)"; break;
        case StatusError::data_length: text = "data length error (the packet is shorter than the item)"; break;
        case StatusError::data_limit: text = "data limit error (the value exceeds a configured limit)"; break;
        case StatusError::access: text = "access error (read-only item, or EEPROM item written with torque on)"; break;
        default: text = "unknown error code " + std::to_string(err_byte & 0x7F); break;
    }
    if (err_byte & kAlertBit) text += std::string(text.empty() ? "" : "; ") + "hardware alert (read Hardware Error Status)";
    return text;
}

std::string describe_hardware_error(std::uint8_t bits) {
    std::string out;
    auto add = [&](std::uint8_t bit, const char* what) {
        if (!(bits & bit)) return;
        if (!out.empty()) out += ", ";
        out += what;
    };
    add(hw_error::input_voltage, "input voltage out of range");
    add(hw_error::overheating, "overheating");
    add(hw_error::motor_encoder, "motor encoder fault");
    add(hw_error::electrical_shock, "electrical shock (circuit damaged?)");
    add(hw_error::overload, "overload");
    const std::uint8_t known = hw_error::input_voltage | hw_error::overheating | hw_error::motor_encoder |
                               hw_error::electrical_shock | hw_error::overload;
    if (bits & ~known) {
        if (!out.empty()) out += ", ";
        out += "unknown bits 0x" + [&] {
            char b[8];
            std::snprintf(b, sizeof b, "%02X", static_cast<unsigned>(bits & ~known));
            return std::string(b);
        }();
    }
    return out;
}

std::uint16_t crc16(std::span<const std::uint8_t> data, std::uint16_t crc) noexcept {
    for (std::uint8_t byte : data)
        crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable[((crc >> 8) ^ byte) & 0xFF]);
    return crc;
}

Bytes stuff(std::span<const std::uint8_t> payload) {
    Bytes out;
    out.reserve(payload.size() + payload.size() / 8);
    for (std::size_t i = 0; i < payload.size(); ++i) {
        out.push_back(payload[i]);
        if (i >= 2 && payload[i] == 0xFD && payload[i - 1] == 0xFF && payload[i - 2] == 0xFF) out.push_back(0xFD);
    }
    return out;
}

Bytes unstuff(std::span<const std::uint8_t> payload) {
    Bytes out;
    out.reserve(payload.size());
    for (std::size_t i = 0; i < payload.size(); ++i) {
        out.push_back(payload[i]);
        const std::size_t n = out.size();
        if (n >= 3 && out[n - 1] == 0xFD && out[n - 2] == 0xFF && out[n - 3] == 0xFF && i + 1 < payload.size() &&
            payload[i + 1] == 0xFD)
            ++i;  // skip the stuffing byte
    }
    return out;
}

Bytes build_instruction(std::uint8_t id, Instruction inst, std::span<const std::uint8_t> params) {
    Bytes payload;
    payload.reserve(params.size() + 1);
    payload.push_back(static_cast<std::uint8_t>(inst));
    payload.insert(payload.end(), params.begin(), params.end());
    return build(id, payload);
}

Bytes build_status(std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> params) {
    Bytes payload;
    payload.reserve(params.size() + 2);
    payload.push_back(static_cast<std::uint8_t>(Instruction::status));
    payload.push_back(error);
    payload.insert(payload.end(), params.begin(), params.end());
    return build(id, payload);
}

void PacketParser::feed(std::span<const std::uint8_t> bytes) {
    compact();
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

void PacketParser::clear() {
    buffer_.clear();
    start_ = 0;
}

void PacketParser::compact() {
    if (start_ > 0) {
        buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
        start_ = 0;
    }
}

std::optional<PacketParser::Output> PacketParser::next() {
    for (;;) {
        // Find a header FF FF FD 00 from start_; everything before it is garbage.
        const std::size_t size = buffer_.size();
        std::size_t h = start_;
        while (h + 4 <= size && !(buffer_[h] == 0xFF && buffer_[h + 1] == 0xFF && buffer_[h + 2] == 0xFD &&
                                  buffer_[h + 3] == 0x00))
            ++h;
        if (h + 4 > size) {
            // Keep a possible partial header (up to 3 bytes) for the next feed.
            std::size_t keep = 0;
            for (std::size_t k = 3; k > 0; --k) {
                if (size >= start_ + k && std::equal(buffer_.end() - static_cast<std::ptrdiff_t>(k), buffer_.end(),
                                                     kHeader.begin())) {
                    keep = k;
                    break;
                }
            }
            discarded_ += size - start_ - keep;
            start_ = size - keep;
            return std::nullopt;
        }
        discarded_ += h - start_;
        start_ = h;
        if (size - start_ < kHeaderSize) return std::nullopt;
        const std::uint8_t id = buffer_[start_ + 4];
        const std::size_t len = get_le(&buffer_[start_ + 5], 2);
        if (len < 3 || len > kMaxPacketLength) {
            // Not a real header (a header-like run inside garbage): skip it.
            start_ += 1;
            discarded_ += 1;
            return Output{Event::bad_length, {}, id};
        }
        if (size - start_ < kHeaderSize + len) return std::nullopt;
        const std::uint8_t* p = &buffer_[start_];
        const std::size_t body = kHeaderSize + len - 2;
        const std::uint16_t want = static_cast<std::uint16_t>(get_le(p + body, 2));
        if (crc16(std::span<const std::uint8_t>(p, body)) != want) {
            start_ += 1;
            discarded_ += 1;
            return Output{Event::crc_mismatch, {}, id};
        }
        Bytes payload = unstuff(std::span<const std::uint8_t>(p + kHeaderSize, len - 2));
        start_ += kHeaderSize + len;
        Output out;
        out.id = id;
        out.packet.id = id;
        out.packet.instruction = payload[0];
        std::size_t first = 1;
        if (out.packet.is_status()) {
            if (payload.size() < 2) return Output{Event::bad_length, {}, id};
            out.packet.error = payload[1];
            first = 2;
        }
        out.packet.params.assign(payload.begin() + static_cast<std::ptrdiff_t>(first), payload.end());
        return out;
    }
}

}  // namespace rollsense::hal::dxl
