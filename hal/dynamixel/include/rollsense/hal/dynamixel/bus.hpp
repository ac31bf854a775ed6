// A Protocol 2.0 bus master over a serial port: one transaction at a time,
// bounded retries on timeouts and CRC errors, typed errors naming the servo.
//
// Retry policy (why): a timeout or a corrupted reply is usually a one-off
// (noise, a late byte), so it is retried `retries` times after dropping any
// stale input; a status packet that reports an error is the servo's considered
// answer and is returned at once, except ERR=3 (the servo saw a corrupted
// instruction), which is noise on our side and retried as well.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rollsense/hal/dynamixel/control_table.hpp"
#include "rollsense/hal/dynamixel/protocol.hpp"
#include "rollsense/hal/serial_link.hpp"
#include "rollsense/hal/serial_port.hpp"
#include "rollsense/status.hpp"

namespace rollsense::hal::dxl {

struct BusOptions {
    std::chrono::microseconds timeout{std::chrono::milliseconds(30)};  // per reply
    int retries = 3;  // extra attempts after the first
};

struct BusStatistics {
    std::uint64_t transactions = 0;
    std::uint64_t retries = 0;
    std::uint64_t timeouts = 0;
    std::uint64_t crc_errors = 0;
    std::uint64_t bytes_sent = 0;
    std::uint64_t bytes_received = 0;
    std::uint64_t garbage_bytes = 0;
    std::uint64_t stale_replies = 0;  // a servo's late reply to an earlier instruction, skipped
};

struct PingReply {
    std::uint8_t id = 0;
    std::uint16_t model_number = 0;
    std::uint8_t firmware = 0;
    bool alert = false;
};

// One servo's reply to a READ or SYNC_READ.
struct ReadReply {
    std::uint8_t id = 0;
    Bytes data;
    bool alert = false;  // the servo has a hardware error (address 70 says which)
};

struct SyncWriteEntry {
    std::uint8_t id = 0;
    Bytes data;  // exactly `length` bytes
};

class Bus {
public:
    Bus(SerialPort port, BusOptions options = {});
    // Any other line, e.g. an emulated bus in memory (VirtualBusLink): reply
    // timeouts and retry pauses run on the link's own clock.
    Bus(std::unique_ptr<SerialLink> link, BusOptions options = {});

    const SerialLink& port() const noexcept { return *port_; }
    SerialLink& port() noexcept { return *port_; }
    const BusOptions& options() const noexcept { return options_; }
    void set_options(const BusOptions& options) { options_ = options; }
    const BusStatistics& statistics() const noexcept { return stats_; }
    // The servo whose reply the last failed transaction lacked (nullopt: the port failed, or none yet).
    std::optional<std::uint8_t> last_failed_id() const noexcept { return last_failed_id_; }
    // The last transaction failed at the port itself (write/read failed: adapter pulled, emulator gone), not at a servo.
    bool port_failed() const noexcept { return port_failed_; }

    Result<PingReply> ping(std::uint8_t id);
    // Ping every id in [first, last] one by one (a broadcast ping's replies
    // collide on some adapters; one by one is slower but always works).
    Result<std::vector<PingReply>> scan(std::uint8_t first, std::uint8_t last,
                                        std::chrono::microseconds per_id_timeout);

    Result<ReadReply> read(std::uint8_t id, std::uint16_t address, std::uint16_t length);
    // Returns whether the reply carried the hardware alert bit.
    Result<bool> write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data);
    // One SYNC_READ: one reply per id, in the order of `ids`.
    Result<std::vector<ReadReply>> sync_read(std::span<const std::uint8_t> ids, std::uint16_t address,
                                             std::uint16_t length);
    // One SYNC_WRITE (broadcast, no reply).
    Status sync_write(std::uint16_t address, std::uint16_t length, std::span<const SyncWriteEntry> entries);
    Status reboot(std::uint8_t id);

    // Typed helpers over read/write for 1, 2 and 4 byte items.
    Result<std::int32_t> read_value(std::uint8_t id, std::uint16_t address, std::uint16_t size);
    Status write_value(std::uint8_t id, std::uint16_t address, std::uint16_t size, std::int64_t value);

private:
    // Send one instruction, collect one status packet from each of `ids` in
    // order, each with `reply_params` parameter bytes (or an error code).
    Result<std::vector<Packet>> transact(std::uint8_t target, Instruction inst, const Bytes& params,
                                         std::span<const std::uint8_t> ids, std::size_t reply_params);
    Status send(const Bytes& packet);
    // Wait for the status packet of `id`; skips echoes, other ids and replies of another length.
    Result<Packet> receive_status(std::uint8_t id, Instruction inst, std::size_t reply_params);

    std::unique_ptr<SerialLink> port_;
    BusOptions options_;
    PacketParser parser_;
    BusStatistics stats_;
    bool port_failed_ = false;  // the last transaction's error came from the port, not a servo
    std::optional<std::uint8_t> last_failed_id_;
};

// "servo 3: data limit error (...)" as a typed error: the ErrorCode follows
// the kind of error (limits, access, hardware, protocol).
Error status_packet_error(std::uint8_t id, Instruction inst, std::uint8_t err_byte);

}  // namespace rollsense::hal::dxl
