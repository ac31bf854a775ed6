// Dynamixel Protocol 2.0 packets: CRC-16, byte stuffing, building and parsing.
//
// Shared by the bus master (plugin side) and the servo emulator (device side),
// so both ends speak exactly the same bytes. Facts: docs/hardware.md §3.
//
//   instruction: FF FF FD 00 | ID | LEN_L LEN_H | INST | PARAMS... | CRC_L CRC_H
//   status:      FF FF FD 00 | ID | LEN_L LEN_H | 0x55 | ERR | PARAMS... | CRC_L CRC_H
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rollsense::hal::dxl {

using Bytes = std::vector<std::uint8_t>;

inline constexpr std::uint8_t kBroadcastId = 0xFE;
inline constexpr std::uint8_t kMaxId = 252;
inline constexpr std::size_t kHeaderSize = 7;     // FF FF FD 00 ID LEN_L LEN_H
inline constexpr std::size_t kMaxPacketLength = 1024;  // LEN field ceiling we accept (resync guard)

enum class Instruction : std::uint8_t {
    ping = 0x01,
    read = 0x02,
    write = 0x03,
    reg_write = 0x04,
    action = 0x05,
    factory_reset = 0x06,
    reboot = 0x08,
    clear = 0x10,
    status = 0x55,
    sync_read = 0x82,
    sync_write = 0x83,
    fast_sync_read = 0x8A,
    bulk_read = 0x92,
    bulk_write = 0x93,
    fast_bulk_read = 0x9A,
};

std::string to_string(Instruction inst);

// The ERR byte of a status packet: bit 7 = hardware alert, low 7 bits = code.
enum class StatusError : std::uint8_t {
    none = 0,
    result_fail = 1,
    instruction = 2,
    crc = 3,
    data_range = 4,
    data_length = 5,
    data_limit = 6,
    access = 7,
};
inline constexpr std::uint8_t kAlertBit = 0x80;

// "data range error: the value is outside the item's range", etc.
std::string describe_status_error(std::uint8_t err_byte);

// Hardware Error Status (address 70) bits and their meaning.
namespace hw_error {
inline constexpr std::uint8_t input_voltage = 0x01;
inline constexpr std::uint8_t overheating = 0x04;
inline constexpr std::uint8_t motor_encoder = 0x08;
inline constexpr std::uint8_t electrical_shock = 0x10;
inline constexpr std::uint8_t overload = 0x20;
}  // namespace hw_error
// "overload, overheating" (comma-separated meanings of the set bits).
std::string describe_hardware_error(std::uint8_t bits);

// CRC-16/BUYPASS: poly 0x8005, init 0, not reflected, no final XOR.
std::uint16_t crc16(std::span<const std::uint8_t> data, std::uint16_t crc = 0) noexcept;

// Insert an FD after every FF FF FD in `payload` (INST..last param).
Bytes stuff(std::span<const std::uint8_t> payload);
// Remove the FD that follows every FF FF FD.
Bytes unstuff(std::span<const std::uint8_t> payload);

// A complete packet on the wire (header, stuffed payload, CRC).
Bytes build_instruction(std::uint8_t id, Instruction inst, std::span<const std::uint8_t> params);
Bytes build_status(std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> params);

// A received packet after unstuffing. For a status packet `instruction` is
// 0x55, `error` the ERR byte and `params` what follows it.
struct Packet {
    std::uint8_t id = 0;
    std::uint8_t instruction = 0;
    std::uint8_t error = 0;  // status packets only
    Bytes params;

    bool is_status() const { return instruction == static_cast<std::uint8_t>(Instruction::status); }
    bool alert() const { return (error & kAlertBit) != 0; }
    std::uint8_t error_code() const { return error & 0x7F; }
};

// Streaming parser: feed it whatever the port delivered; take packets out.
// It resynchronises on garbage by searching for the next FF FF FD 00 header,
// and on a CRC mismatch drops that header and searches again.
class PacketParser {
public:
    enum class Event { packet, crc_mismatch, bad_length };
    struct Output {
        Event event = Event::packet;
        Packet packet;     // valid when event == packet
        std::uint8_t id = 0;  // the header's ID (all events)
    };

    void feed(std::span<const std::uint8_t> bytes);
    // The next complete packet or error, or nullopt if more bytes are needed.
    std::optional<Output> next();
    void clear();

    // Bytes thrown away while searching for a header (for statistics).
    std::size_t discarded() const noexcept { return discarded_; }
    std::size_t buffered() const noexcept { return buffer_.size() - start_; }

private:
    void compact();
    Bytes buffer_;
    std::size_t start_ = 0;
    std::size_t discarded_ = 0;
};

// Little-endian helpers.
inline void put_u16(Bytes& out, std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v & 0xFF));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
}
inline void put_u32(Bytes& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}
inline void put_le(Bytes& out, std::int64_t v, std::size_t size) {
    const auto u = static_cast<std::uint64_t>(v);
    for (std::size_t i = 0; i < size; ++i) out.push_back(static_cast<std::uint8_t>((u >> (8 * i)) & 0xFF));
}
// Unsigned little-endian value of `size` bytes at `p`.
inline std::uint32_t get_le(const std::uint8_t* p, std::size_t size) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < size; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
    return v;
}
// Sign-extended value of a 1, 2 or 4 byte item.
inline std::int32_t get_le_signed(const std::uint8_t* p, std::size_t size) {
    const std::uint32_t v = get_le(p, size);
    if (size == 1) return static_cast<std::int8_t>(v);
    if (size == 2) return static_cast<std::int16_t>(v);
    return static_cast<std::int32_t>(v);
}

}  // namespace rollsense::hal::dxl
