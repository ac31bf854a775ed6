#include "rollsense/hal/dynamixel/bus_emulator.hpp"

#include <algorithm>

namespace rollsense::hal::dxl {
namespace {
constexpr auto E_INSTRUCTION = static_cast<std::uint8_t>(StatusError::instruction);
constexpr auto E_LENGTH = static_cast<std::uint8_t>(StatusError::data_length);
constexpr auto E_CRC = static_cast<std::uint8_t>(StatusError::crc);
}  // namespace

void BusEmulator::add_servo(const ServoSetup& setup) { servos_.emplace_back(setup); }

EmulatedServo* BusEmulator::servo(std::uint8_t id) {
    for (auto& s : servos_)
        if (s.id() == id) return &s;
    return nullptr;
}
const EmulatedServo* BusEmulator::servo(std::uint8_t id) const {
    for (const auto& s : servos_)
        if (s.id() == id) return &s;
    return nullptr;
}

bool BusEmulator::hears(const EmulatedServo& s) const {
    if (line_baud_ == 0) return true;
    return baud_from_index(static_cast<std::uint8_t>(s.item(addr::baud_rate, 1))) == line_baud_;
}

EmulatedServo* BusEmulator::listener(std::uint8_t id) {
    auto* s = servo(id);
    return s && hears(*s) ? s : nullptr;
}

std::vector<std::uint8_t> BusEmulator::ids() const {
    std::vector<std::uint8_t> out;
    for (const auto& s : servos_) out.push_back(s.id());
    return out;
}

std::chrono::microseconds BusEmulator::late_by(std::uint8_t id) const {
    const auto it = faults_.find(id);
    return it == faults_.end() ? std::chrono::microseconds{0} : it->second.late;
}

void BusEmulator::apply_due_faults() {
    for (auto& s : scheduled_) {
        if (s.applied || elapsed_ + 1e-9 < s.fault.after_s) continue;
        s.applied = true;
        auto& plan = faults_[s.fault.id];
        switch (s.fault.kind) {
            case FaultKind::silent: plan.drop_replies = -1; break;
            case FaultKind::corrupt: plan.corrupt_replies = -1; break;
            case FaultKind::slow: plan.late = kLateBy; break;
            case FaultKind::hardware_error: raise_hardware_error(s.fault.id, hw_error::overload); break;
        }
    }
}

void BusEmulator::advance(double seconds) {
    elapsed_ += seconds;
    apply_due_faults();
    if (!coupling_) {
        for (auto& s : servos_) s.step(seconds);
        return;
    }
    // The coupled obstacles move with the servos: re-place them at the servos'
    // own integration step so the coupling does not lag.
    while (seconds > 1e-12) {
        const double dt = std::min(seconds, kCouplingStep);
        coupling_(*this);
        for (auto& s : servos_) s.step(dt);
        seconds -= dt;
    }
    coupling_(*this);
}

void BusEmulator::raise_hardware_error(std::uint8_t id, std::uint8_t bits) {
    if (auto* s = servo(id)) s->raise_hardware_error(bits);
}

bool BusEmulator::reply(EmulatedServo& s, std::uint8_t error, std::span<const std::uint8_t> params,
                        std::vector<Bytes>& out) {
    auto& plan = faults_[s.id()];
    if (plan.drop_replies != 0) {
        if (plan.drop_replies > 0) --plan.drop_replies;
        return false;
    }
    Bytes packet = build_status(s.id(), static_cast<std::uint8_t>(error | s.alert_bits()), params);
    if (plan.corrupt_replies != 0) {
        if (plan.corrupt_replies > 0) --plan.corrupt_replies;
        packet.back() ^= 0x5A;
    }
    if (!garbage_.empty()) {
        packet.insert(packet.begin(), garbage_.begin(), garbage_.end());
        garbage_.clear();
    }
    out.push_back(std::move(packet));
    return true;
}

std::vector<Bytes> BusEmulator::receive(std::span<const std::uint8_t> bytes) {
    parser_.feed(bytes);
    std::vector<Bytes> out;
    while (auto p = parser_.next()) {
        if (p->event == PacketParser::Event::crc_mismatch) {
            // A servo that recognises its id in a corrupted packet says so.
            ++crc_errors_;
            if (auto* s = listener(p->id)) reply(*s, E_CRC, {}, out);
            continue;
        }
        if (p->event != PacketParser::Event::packet || p->packet.is_status()) continue;
        auto replies = handle(p->packet);
        for (auto& r : replies) out.push_back(std::move(r));
    }
    return out;
}

std::vector<Bytes> BusEmulator::handle(const Packet& in) {
    ++handled_;
    std::vector<Bytes> out;
    const bool broadcast = in.id == kBroadcastId;
    const auto& prm = in.params;
    // Every servo the packet reaches restarts its Bus Watchdog count.
    if (broadcast) {
        for (auto& s : servos_)
            if (hears(s)) s.heard_instruction();
    } else if (auto* s = listener(in.id)) {
        s->heard_instruction();
    }
    auto targets = [&]() {
        std::vector<EmulatedServo*> t;
        if (broadcast) {
            for (auto& s : servos_)
                if (hears(s)) t.push_back(&s);
        } else if (auto* s = listener(in.id)) {
            t.push_back(s);
        }
        return t;
    };

    switch (static_cast<Instruction>(in.instruction)) {
        case Instruction::ping:
            // Broadcast ping: every servo answers, in id order.
            for (auto* s : [&] {
                     auto t = targets();
                     std::sort(t.begin(), t.end(), [](auto* a, auto* b) { return a->id() < b->id(); });
                     return t;
                 }()) {
                Bytes params;
                put_u16(params, static_cast<std::uint16_t>(s->item(addr::model_number, 2)));
                params.push_back(static_cast<std::uint8_t>(s->item(addr::firmware_version, 1)));
                reply(*s, 0, params, out);
            }
            return out;
        case Instruction::read: {
            if (broadcast) return out;  // no reply to a broadcast READ
            auto* s = listener(in.id);
            if (!s) return out;
            if (prm.size() != 4) {
                reply(*s, E_LENGTH, {}, out);
                return out;
            }
            Bytes data;
            const auto err = s->read(static_cast<std::uint16_t>(get_le(&prm[0], 2)),
                                     static_cast<std::uint16_t>(get_le(&prm[2], 2)), data);
            reply(*s, err, err ? Bytes{} : data, out);
            return out;
        }
        case Instruction::write: {
            for (auto* s : targets()) {
                const auto err = prm.size() < 3
                                     ? E_LENGTH
                                     : s->write(static_cast<std::uint16_t>(get_le(&prm[0], 2)),
                                                std::span<const std::uint8_t>(prm).subspan(2));
                if (!broadcast) reply(*s, err, {}, out);
            }
            return out;
        }
        case Instruction::reboot: {
            if (broadcast) {
                for (auto& s : servos_)
                    if (hears(s)) s.reboot();
                return out;
            }
            if (auto* s = listener(in.id)) {
                reply(*s, 0, {}, out);  // the servo answers, then restarts
                s->reboot();
            }
            return out;
        }
        case Instruction::sync_write: {
            ++sync_writes_;
            if (!broadcast || prm.size() < 4) return out;
            const std::size_t address = get_le(&prm[0], 2), length = get_le(&prm[2], 2);
            if (length == 0 || (prm.size() - 4) % (length + 1) != 0) return out;  // malformed: ignored, as broadcast
            for (std::size_t at = 4; at < prm.size(); at += length + 1)
                if (auto* s = listener(prm[at]))
                    (void)s->write(static_cast<std::uint16_t>(address),
                                   std::span<const std::uint8_t>(prm).subspan(at + 1, length));
            return out;
        }
        case Instruction::sync_read: {
            ++sync_reads_;
            if (!broadcast || prm.size() < 5) return out;
            const auto address = static_cast<std::uint16_t>(get_le(&prm[0], 2));
            const auto length = static_cast<std::uint16_t>(get_le(&prm[2], 2));
            for (std::size_t at = 4; at < prm.size(); ++at) {
                auto* s = listener(prm[at]);
                if (!s) continue;
                Bytes data;
                const auto err = s->read(address, length, data);
                reply(*s, err, err ? Bytes{} : data, out);
            }
            return out;
        }
        default:
            // REG_WRITE/ACTION, FACTORY_RESET, CLEAR, BULK_* and unknown
            // instructions are not emulated: say so, as firmware does for unknown ones.
            if (!broadcast)
                if (auto* s = listener(in.id)) reply(*s, E_INSTRUCTION, {}, out);
            return out;
    }
}

}  // namespace rollsense::hal::dxl
