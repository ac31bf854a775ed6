#include "rollsense/hal/dynamixel/bus.hpp"

#include <array>
#include <optional>

namespace rollsense::hal::dxl {
namespace {

std::string servo(std::uint8_t id) { return "servo " + std::to_string(id); }

enum class Failure { none, timeout, crc, other };

}  // namespace

Error status_packet_error(std::uint8_t id, Instruction inst, std::uint8_t err_byte) {
    ErrorCode code = ErrorCode::protocol_error;
    switch (static_cast<StatusError>(err_byte & 0x7F)) {
        case StatusError::result_fail: code = ErrorCode::hardware_fault; break;
        case StatusError::data_range:
        case StatusError::data_limit: code = ErrorCode::limit_violation; break;
        case StatusError::access: code = ErrorCode::state_error; break;
        default: code = ErrorCode::protocol_error; break;
    }
    return Error{code, servo(id) + " refused " + to_string(inst) + ": " + describe_status_error(err_byte)};
}

Bus::Bus(SerialPort port, BusOptions options)
    : Bus(std::make_unique<SerialPort>(std::move(port)), options) {}

Bus::Bus(std::unique_ptr<SerialLink> link, BusOptions options) : port_(std::move(link)), options_(options) {}

Status Bus::send(const Bytes& packet) {
    stats_.bytes_sent += packet.size();
    auto st = port_->write_all(packet);
    port_failed_ = !st.ok();
    return st;
}

Result<Packet> Bus::receive_status(std::uint8_t id, Instruction inst, std::size_t reply_params) {
    const auto deadline = port_->now() + options_.timeout;
    std::array<std::uint8_t, 512> buf{};
    std::optional<std::size_t> other_length;  // of a reply skipped as another instruction's
    for (;;) {
        while (auto out = parser_.next()) {
            if (out->event == PacketParser::Event::crc_mismatch) {
                ++stats_.crc_errors;
                return Error{ErrorCode::protocol_error,
                             servo(id) + ": reply to " + to_string(inst) + " failed its CRC check"};
            }
            if (out->event != PacketParser::Event::packet) continue;
            const Packet& p = out->packet;
            // Adapters that echo our own instruction (and other servos' late
            // replies) are not the packet we wait for; nor is a late reply of
            // this servo to an earlier instruction (the rest of a SYNC_READ cut
            // short by a fault), told apart by its length: a status packet
            // does not say which instruction it answers.
            if (!p.is_status() || p.id != id) continue;
            if (p.error_code() == 0 && p.params.size() != reply_params) {
                ++stats_.stale_replies;
                other_length = p.params.size();
                continue;
            }
            return std::move(out->packet);
        }
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - port_->now());
        if (left.count() <= 0 && other_length)  // it answered, but not with what was asked: not a wiring fault
            return Error{ErrorCode::protocol_error, servo(id) + " answered " + to_string(inst) + " with " +
                                                        std::to_string(*other_length) + " bytes of data, not the " +
                                                        std::to_string(reply_params) + " asked for"};
        if (left.count() <= 0) {
            ++stats_.timeouts;
            return Error{ErrorCode::timeout, servo(id) + " did not answer " + to_string(inst) + " within " +
                                                 std::to_string(options_.timeout.count() / 1000.0).substr(0, 5) +
                                                 " ms"};
        }
        auto n = port_->read_some(buf, left);
        if (!n.ok()) {
            port_failed_ = true;
            return n.error();
        }
        stats_.bytes_received += *n;
        parser_.feed(std::span<const std::uint8_t>(buf.data(), *n));
    }
}

Result<std::vector<Packet>> Bus::transact(std::uint8_t target, Instruction inst, const Bytes& params,
                                          std::span<const std::uint8_t> ids, std::size_t reply_params) {
    const Bytes packet = build_instruction(target, inst, params);
    // Protocol 2.0 has no sequence numbers: a duplicate reply left over from
    // an earlier retried transaction would pass for this one's answer. Start clean.
    (void)port_->discard_input();
    parser_.clear();
    last_failed_id_.reset();
    Error last;
    for (int attempt = 0; attempt <= options_.retries; ++attempt) {
        if (attempt > 0) {
            ++stats_.retries;
            // A late reply to the failed attempt must not be taken for the
            // answer to this one: wait out one byte time and drop everything.
            port_->pause(port_->byte_time() * 20);
            (void)port_->discard_input();
            parser_.clear();
        }
        ++stats_.transactions;
        if (auto st = send(packet); !st.ok()) return st;
        std::vector<Packet> replies;
        Failure failure = Failure::none;
        for (std::uint8_t id : ids) {
            auto reply = receive_status(id, inst, reply_params);
            if (!port_failed_) last_failed_id_ = id;  // until its reply passes
            if (!reply.ok()) {
                last = reply.error();
                failure = reply.error().code == ErrorCode::timeout        ? Failure::timeout
                          : reply.error().code == ErrorCode::protocol_error ? Failure::crc
                                                                           : Failure::other;
                break;
            }
            if (reply->error_code() == static_cast<std::uint8_t>(StatusError::crc)) {
                last = status_packet_error(id, inst, reply->error);
                failure = Failure::crc;
                break;
            }
            if (reply->error_code() != 0) return status_packet_error(id, inst, reply->error);
            last_failed_id_.reset();
            replies.push_back(std::move(reply).value());
        }
        stats_.garbage_bytes = parser_.discarded();
        if (failure == Failure::none) return replies;
        if (failure == Failure::other) return last;
    }
    std::string hint = last.code == ErrorCode::timeout
                           ? "; check the servo's power, its id, the bus baud rate and the wiring (rollsense dxl scan)"
                           : "; noise on the bus? check cabling, grounding and the baud rate";
    return Error{last.code, last.message + " (" + std::to_string(options_.retries + 1) + " attempts)" + hint};
}

Result<PingReply> Bus::ping(std::uint8_t id) {
    const std::uint8_t ids[] = {id};
    auto r = transact(id, Instruction::ping, {}, ids, 3);  // model number, firmware
    if (!r.ok()) return r.error();
    const Packet& p = r->front();
    return PingReply{id, static_cast<std::uint16_t>(get_le(p.params.data(), 2)), p.params[2], p.alert()};
}

Result<std::vector<PingReply>> Bus::scan(std::uint8_t first, std::uint8_t last,
                                         std::chrono::microseconds per_id_timeout) {
    const BusOptions saved = options_;
    options_.timeout = per_id_timeout;
    options_.retries = 0;
    std::vector<PingReply> found;
    for (unsigned id = first; id <= last && id <= kMaxId; ++id) {
        auto r = ping(static_cast<std::uint8_t>(id));
        if (r.ok()) {
            found.push_back(*r);
        } else if (port_failed_) {  // the adapter is gone; a servo's refusal or a garbled reply is one id's
            options_ = saved;
            return r.error();
        }
    }
    options_ = saved;
    return found;
}

Result<ReadReply> Bus::read(std::uint8_t id, std::uint16_t address, std::uint16_t length) {
    Bytes params;
    put_u16(params, address);
    put_u16(params, length);
    const std::uint8_t ids[] = {id};
    auto r = transact(id, Instruction::read, params, ids, length);
    if (!r.ok()) return r.error();
    Packet& p = r->front();
    return ReadReply{id, std::move(p.params), p.alert()};
}

Result<bool> Bus::write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data) {
    Bytes params;
    put_u16(params, address);
    params.insert(params.end(), data.begin(), data.end());
    if (id == kBroadcastId) {
        if (auto st = send(build_instruction(id, Instruction::write, params)); !st.ok()) return st;
        return false;
    }
    const std::uint8_t ids[] = {id};
    auto r = transact(id, Instruction::write, params, ids, 0);
    if (!r.ok()) return r.error();
    return r->front().alert();
}

Result<std::vector<ReadReply>> Bus::sync_read(std::span<const std::uint8_t> ids, std::uint16_t address,
                                              std::uint16_t length) {
    Bytes params;
    put_u16(params, address);
    put_u16(params, length);
    params.insert(params.end(), ids.begin(), ids.end());
    auto r = transact(kBroadcastId, Instruction::sync_read, params, ids, length);
    if (!r.ok()) return r.error();
    std::vector<ReadReply> out;
    out.reserve(r->size());
    for (auto& p : *r) out.push_back(ReadReply{p.id, std::move(p.params), p.alert()});
    return out;
}

Status Bus::sync_write(std::uint16_t address, std::uint16_t length, std::span<const SyncWriteEntry> entries) {
    Bytes params;
    put_u16(params, address);
    put_u16(params, length);
    for (const auto& e : entries) {
        if (e.data.size() != length)
            return {ErrorCode::invalid_argument, "SYNC_WRITE entry for " + servo(e.id) + " has " +
                                                     std::to_string(e.data.size()) + " bytes, expected " +
                                                     std::to_string(length)};
        params.push_back(e.id);
        params.insert(params.end(), e.data.begin(), e.data.end());
    }
    ++stats_.transactions;
    return send(build_instruction(kBroadcastId, Instruction::sync_write, params));
}

Status Bus::reboot(std::uint8_t id) {
    const std::uint8_t ids[] = {id};
    auto r = transact(id, Instruction::reboot, {}, ids, 0);
    return r.status();
}

Result<std::int32_t> Bus::read_value(std::uint8_t id, std::uint16_t address, std::uint16_t size) {
    auto r = read(id, address, size);
    if (!r.ok()) return r.error();
    return get_le_signed(r->data.data(), size);
}

Status Bus::write_value(std::uint8_t id, std::uint16_t address, std::uint16_t size, std::int64_t value) {
    Bytes data;
    put_le(data, value, size);
    return write(id, address, data).status();
}

}  // namespace rollsense::hal::dxl
