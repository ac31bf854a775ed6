// rollsense-dxl-emu: a bus of emulated X-series servos on a pseudo-terminal.
//
//   rollsense-dxl-emu [--servo ID:MODEL[:START_DEG[:MODE[:CONTACT_DEG]]]]... [--link PATH]
//                     [--wire-baud N] [--status-every SECONDS]
//
// Without --servo it emulates the E-TRoll bus (ids 1-4). It prints the pty
// path (and makes --link a symlink to it) so a profile can point its `device`
// there; it runs until Ctrl-C.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"

using namespace rollsense::hal::dxl;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

int usage(const char* why) {
    if (why) std::fprintf(stderr, "rollsense-dxl-emu: %s\n", why);
    std::fprintf(stderr,
                 "usage: rollsense-dxl-emu [--servo ID:MODEL[:START_DEG[:MODE[:CONTACT_DEG]]]]... [--link PATH]\n"
                 "                         [--wire-baud N] [--status-every SECONDS]\n"
                 "  --servo         one emulated servo (repeatable); default: the E-TRoll bus,\n"
                 "                  1-3 XM430-W350 (position), 4 XL330-M288 (extended_position)\n"
                 "                  MODE: position|extended_position|current|current_based_position|velocity\n"
                 "  --link PATH     also create PATH as a symlink to the pty (removed on exit)\n"
                 "  --wire-baud N   delay replies as a real bus at N baud would (default: instant)\n"
                 "  --status-every  print every servo's state each SECONDS (default: off)\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    BusEmulator bus;
    bool any = false;
    std::string link;
    PtyEmulatorOptions options;
    double status_every = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
        if (a == "--help" || a == "-h") return usage(nullptr), 0;
        if (a == "--servo") {
            const char* v = value();
            if (!v) return usage("--servo needs a value");
            auto s = parse_servo_spec(v);
            if (!s.ok()) return usage(s.error().message.c_str());
            if (bus.servo(s->id)) return usage(("servo id " + std::to_string(s->id) + " given twice").c_str());
            bus.add_servo(*s);
            any = true;
        } else if (a == "--link") {
            const char* v = value();
            if (!v) return usage("--link needs a path");
            link = v;
        } else if (a == "--wire-baud") {
            const char* v = value();
            if (!v) return usage("--wire-baud needs a rate");
            options.wire_baud = static_cast<std::uint32_t>(std::strtoul(v, nullptr, 10));
        } else if (a == "--status-every") {
            const char* v = value();
            if (!v) return usage("--status-every needs seconds");
            status_every = std::strtod(v, nullptr);
        } else {
            return usage(("unknown argument '" + a + "'").c_str());
        }
    }
    if (!any)
        for (const auto& s : etroll_servos()) bus.add_servo(s);

    auto emu = PtyBusEmulator::start(std::move(bus), options);
    if (!emu.ok()) {
        std::fprintf(stderr, "rollsense-dxl-emu: %s\n", emu.error().message.c_str());
        return 4;
    }
    auto& e = **emu;
    if (!link.empty()) {
        ::unlink(link.c_str());
        if (::symlink(e.device().c_str(), link.c_str()) != 0) {
            std::fprintf(stderr, "rollsense-dxl-emu: cannot create link %s: %s\n", link.c_str(), std::strerror(errno));
            return 4;
        }
    }
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::printf("%s\n", link.empty() ? e.device().c_str() : link.c_str());
    e.with_bus([](BusEmulator& b) {
        for (auto id : b.ids()) {
            const auto* s = b.servo(id);
            std::fprintf(stderr, "servo %u: %s, %s mode, at %.1f deg\n", id, std::string(s->model().name).c_str(),
                         to_string(s->mode()).c_str(), ticks_to_degrees(s->position_ticks()));
        }
        return 0;
    });
    std::fflush(stdout);
    auto next_status = std::chrono::steady_clock::now();
    while (!g_stop) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        if (status_every > 0 && std::chrono::steady_clock::now() >= next_status) {
            next_status += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                std::chrono::duration<double>(status_every));
            e.with_bus([](BusEmulator& b) {
                for (auto id : b.ids()) {
                    const auto* s = b.servo(id);
                    std::fprintf(stderr, "[%u %s torque=%d pos=%.2fdeg cur=%.0fmA hw=0x%02X] ", id,
                                 to_string(s->mode()).c_str(), s->torque_enabled() ? 1 : 0,
                                 ticks_to_degrees(s->position_ticks()), s->current_ma(), s->hardware_error());
                }
                std::fprintf(stderr, "\n");
                return 0;
            });
        }
    }
    e.stop();
    if (!link.empty()) ::unlink(link.c_str());
    return 0;
}
