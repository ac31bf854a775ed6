#include "rollsense/hal/dynamixel/virtual_link.hpp"

#include <algorithm>
#include <cstring>

namespace rollsense::hal::dxl {

VirtualBusLink::VirtualBusLink(BusEmulator bus, std::uint32_t baud, std::string name)
    : bus_(std::move(bus)), baud_(baud), name_(std::move(name)) {
    bus_.set_line_baud(baud_);
}

Status VirtualBusLink::set_baud(std::uint32_t baud) {
    if (baud == 0) return {ErrorCode::invalid_argument, name_ + ": baud rate 0 is not a rate"};
    baud_ = baud;
    bus_.set_line_baud(baud);  // servos at another rate hear only noise, as on a wire
    return {};
}

Status VirtualBusLink::write_all(std::span<const std::uint8_t> bytes, std::chrono::milliseconds) {
    for (auto& packet : bus_.receive(bytes)) {
        const auto late = packet.size() > 4 ? bus_.late_by(packet[4]) : std::chrono::microseconds{0};
        const Clock::time_point due = now_ + late;
        // Keep the queue in due order; replies due together keep the servos' order.
        auto at = std::find_if(replies_.begin(), replies_.end(), [&](const Reply& r) { return r.due > due; });
        replies_.insert(at, Reply{due, std::move(packet)});
    }
    return {};
}

std::size_t VirtualBusLink::take_due(std::span<std::uint8_t> buffer) {
    std::size_t n = 0;
    while (n < buffer.size() && !replies_.empty() && replies_.front().due <= now_) {
        Reply& r = replies_.front();
        const std::size_t k = std::min(buffer.size() - n, r.bytes.size() - r.read);
        std::memcpy(buffer.data() + n, r.bytes.data() + r.read, k);
        n += k;
        r.read += k;
        if (r.read == r.bytes.size()) replies_.pop_front();
    }
    return n;
}

Result<std::size_t> VirtualBusLink::read_some(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout) {
    if (buffer.empty()) return std::size_t{0};
    if (const auto n = take_due(buffer); n > 0) return n;
    const Clock::time_point deadline = now_ + timeout;
    if (!replies_.empty() && replies_.front().due <= deadline) {
        now_ = replies_.front().due;  // wait for the late reply, no longer
        return take_due(buffer);
    }
    now_ = std::max(now_, deadline);  // nothing comes: the whole timeout passes
    return std::size_t{0};
}

Status VirtualBusLink::discard_input() {
    // Only what has arrived: a reply still on its way (a slow servo) lands later.
    while (!replies_.empty() && replies_.front().due <= now_) replies_.pop_front();
    return {};
}

void VirtualBusLink::advance_servos_to(double seconds) {
    if (servo_time_ && seconds > *servo_time_) bus_.advance(seconds - *servo_time_);
    if (!servo_time_ || seconds > *servo_time_) servo_time_ = seconds;
}

std::size_t VirtualBusLink::pending_bytes() const {
    std::size_t n = 0;
    for (const auto& r : replies_) n += r.bytes.size() - r.read;
    return n;
}

}  // namespace rollsense::hal::dxl
