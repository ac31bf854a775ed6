#include "rollsense/hal/dynamixel/pty_emulator.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <array>

#include "rollsense/hal/baud_rate.hpp"
#include <cerrno>

namespace rollsense::hal::dxl {

Result<std::unique_ptr<PtyBusEmulator>> PtyBusEmulator::start(BusEmulator bus, PtyEmulatorOptions options) {
    auto pty = PtyPair::open();
    if (!pty.ok()) return pty.error();
    std::unique_ptr<PtyBusEmulator> emu(new PtyBusEmulator(std::move(pty).value(), std::move(bus), options));
    emu->running_ = true;
    emu->thread_ = std::thread([e = emu.get()] { e->serve(); });
    return emu;
}

PtyBusEmulator::~PtyBusEmulator() { stop(); }

void PtyBusEmulator::stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
}

void PtyBusEmulator::send(const Bytes& bytes) {
    std::size_t done = 0;
    while (done < bytes.size() && running_) {
        const ssize_t n = ::write(pty_.master_fd(), bytes.data() + done, bytes.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
        } else if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
            pollfd p{pty_.master_fd(), POLLOUT, 0};
            ::poll(&p, 1, 5);
        } else {
            return;
        }
    }
}

void PtyBusEmulator::serve() {
    using Clock = std::chrono::steady_clock;
    auto last = Clock::now();
    std::array<std::uint8_t, 4096> buf{};
    while (running_) {
        pollfd p{pty_.master_fd(), POLLIN, 0};
        const int r = ::poll(&p, 1, 2);
        const auto now = Clock::now();
        std::vector<Bytes> replies;
        std::vector<std::chrono::nanoseconds> delays;
        {
            std::lock_guard lock(mutex_);
            if (options_.real_time) {
                bus_.advance(std::chrono::duration<double>(now - last).count());
            }
            last = now;
            if (r > 0 && (p.revents & POLLIN)) {
                const ssize_t n = ::read(pty_.master_fd(), buf.data(), buf.size());
                if (n > 0) {
                    std::uint32_t wire_baud = options_.wire_baud;
                    if (auto line = query_baud(pty_.slave_fd()); line.ok()) {
                        bus_.set_line_baud(*line);
                        if (options_.wire_baud_from_line) wire_baud = *line;
                    }
                    replies = bus_.receive(std::span<const std::uint8_t>(buf.data(), static_cast<std::size_t>(n)));
                    bytes_handled_ += static_cast<std::uint64_t>(n);
                    // A `slow` servo's reply goes to the late queue; the
                    // thread keeps serving the others meanwhile.
                    for (auto it = replies.begin(); it != replies.end();) {
                        const auto late = it->size() > 4 ? bus_.late_by((*it)[4]) : std::chrono::microseconds{0};
                        if (late.count() > 0) {
                            late_.push_back({now + late, std::move(*it)});
                            it = replies.erase(it);
                        } else {
                            ++it;
                        }
                    }
                    if (wire_baud > 0) {
                        // Instruction on the wire, then each servo's return delay and reply.
                        const auto byte_ns = 10'000'000'000LL / wire_baud;
                        std::chrono::nanoseconds at(static_cast<long long>(n) * byte_ns);
                        for (const auto& rep : replies) {
                            const auto* s = rep.size() > 4 ? bus_.servo(rep[4]) : nullptr;
                            if (s) at += std::chrono::microseconds(2 * static_cast<std::uint8_t>(s->item(addr::return_delay_time, 1)));
                            at += std::chrono::nanoseconds(static_cast<long long>(rep.size()) * byte_ns);
                            delays.push_back(at);
                        }
                    }
                }
            }
        }
        for (std::size_t i = 0; i < replies.size(); ++i) {
            if (!delays.empty()) std::this_thread::sleep_until(now + delays[i]);
            send(replies[i]);
        }
        while (!late_.empty() && late_.front().due <= Clock::now()) {
            send(late_.front().bytes);
            late_.pop_front();
        }
    }
}

}  // namespace rollsense::hal::dxl
