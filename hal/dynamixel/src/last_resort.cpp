#include "rollsense/hal/dynamixel/last_resort.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <mutex>

#include "rollsense/last_resort.hpp"

namespace rollsense::hal::dxl {
namespace {

constexpr int kSlots = 8;
struct Slot {
    std::atomic<int> fd{-1};  // -1: free; set last, after the bytes
    std::size_t length = 0;
    std::uint8_t bytes[kLastResortPacketMax] = {};
};
Slot g_slots[kSlots];
constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGABRT, SIGFPE};
struct sigaction g_previous[sizeof kSignals / sizeof kSignals[0]];
std::mutex g_register;

void send_prepared(void*) noexcept {
    for (auto& s : g_slots) {
        const int fd = s.fd.load();
        if (fd < 0) continue;
        for (int copy = 0; copy < 2; ++copy) (void)!::write(fd, s.bytes, s.length);
    }
}

extern "C" void on_crash(int sig) {
    send_prepared(nullptr);
    static const char msg[] = "\nrollsense: crashed; torque-off sent to every Dynamixel bus\n";
    (void)!::write(STDERR_FILENO, msg, sizeof msg - 1);
    // Hand the signal on: the previous handler, or the default action.
    for (std::size_t i = 0; i < sizeof kSignals / sizeof kSignals[0]; ++i)
        if (kSignals[i] == sig) ::sigaction(sig, &g_previous[i], nullptr);
    ::raise(sig);
}

// (Re)install where someone else took the signal since (a test framework
// does, per test case); whatever was there is handed the signal after us.
void install() {
    struct sigaction sa {};
    sa.sa_handler = &on_crash;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND | SA_NODEFER;
    for (std::size_t i = 0; i < sizeof kSignals / sizeof kSignals[0]; ++i) {
        struct sigaction now {};
        ::sigaction(kSignals[i], nullptr, &now);
        if (now.sa_handler == &on_crash) continue;
        ::sigaction(kSignals[i], &sa, &g_previous[i]);
    }
}

}  // namespace

int register_last_resort(int fd, std::span<const std::uint8_t> packet) {
    if (fd < 0 || packet.size() > kLastResortPacketMax) return -1;
    std::lock_guard lock(g_register);
    install();
    // The kernel's own last resort (Lua panic, std::terminate, std::bad_alloc,
    // a watchdog that cannot get the bus) sends the same packets.
    static const int kernel_slot = add_last_resort(&send_prepared, nullptr);
    (void)kernel_slot;
    for (int i = 0; i < kSlots; ++i) {
        auto& s = g_slots[i];
        if (s.fd.load() >= 0) continue;
        std::copy(packet.begin(), packet.end(), s.bytes);
        s.length = packet.size();
        s.fd.store(fd);
        return i;
    }
    return -1;
}

void unregister_last_resort(int slot) {
    if (slot < 0 || slot >= kSlots) return;
    g_slots[slot].fd.store(-1);
}

}  // namespace rollsense::hal::dxl
