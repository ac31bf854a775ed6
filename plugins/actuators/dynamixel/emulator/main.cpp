// rollsense-dxl-emu: a bus of emulated X-series servos on a pseudo-terminal.
//
//   rollsense-dxl-emu [--servo ID:MODEL[:START_DEG[:MODE[:CONTACT_DEG]]]]... [--link PATH]
//                     [--object WIDTH_MM|none] [--finger-offset-sum MM] [--array-distance MM]
//                     [--palm MM_PER_DEG:CENTRE_MM]
//                     [--baud N] [--return-delay-us N] [--wire-baud N|line|0]
//                     [--status-every SECONDS] [--inject ID:KIND:AFTER_S]...
//
// Without --servo it emulates the E-TRoll bus (ids 1-4) holding an object
// between the fingers (plugins/common/etroll_hand: the E-TRoll hand's geometry,
// the simulation's calibrated values by default). It prints the pty
// path (and makes --link a symlink to it) so a profile can point its `device`
// there; it runs until Ctrl-C.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rollsense/etroll_hand/clamped_object.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"

using namespace rollsense::hal::dxl;
using rollsense::etroll::ClampedObject;

namespace {

volatile std::sig_atomic_t g_stop = 0;

// A whole string that is a positive number of mm.
bool positive_mm(const char* text, double& out) {
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(v > 0)) return false;
    out = v;
    return true;
}
void on_signal(int) { g_stop = 1; }

int usage(const char* why) {
    if (why) std::fprintf(stderr, "rollsense-dxl-emu: %s\n", why);
    const ClampedObject d;  // the defaults: the E-TRoll hand's geometry, in one place
    std::fprintf(stderr,
                 "usage: rollsense-dxl-emu [--servo ID:MODEL[:START_DEG[:MODE[:CONTACT_DEG]]]]... [--link PATH]\n"
                 "                         [--object WIDTH_MM|none] [--finger-offset-sum MM] [--array-distance MM]\n"
                 "                         [--palm MM_PER_DEG:CENTRE_MM]\n"
                 "                         [--baud N] [--return-delay-us N] [--wire-baud N|line|0]\n"
                 "                         [--status-every SECONDS] [--inject ID:KIND:AFTER_S]...\n"
                 "  --servo         one emulated servo (repeatable); default: the E-TRoll bus,\n"
                 "                  1-3 XM430-W350 (position), 4 XL330-M288 (extended_position)\n"
                 "                  MODE: position|extended_position|current|current_based_position|velocity\n"
                 "  --link PATH     also create PATH as a symlink to the pty (removed on exit)\n"
                 "  --object        an object between the fingers (servos 1 sensing, 2 pushing, 3 palm):\n"
                 "                  its width between the finger surfaces in mm; default %g (the mean\n"
                 "                  flat width of the paper's objects) on the E-TRoll bus, none with --servo\n"
                 "  --finger-offset-sum  the hand: joint axis to contact surface, both fingers summed,\n"
                 "                  mm (default %g, the simulation's calibrated value)\n"
                 "  --array-distance  the hand: along a finger from its joint to the contact (barometer 2),\n"
                 "                  mm (default %g, the simulation's calibrated value)\n"
                 "  --palm          palm width per palm-servo degree and at its centre tick\n"
                 "                  (default %.3f:%g, the etroll profile's radius 10, ratio 2, offset 65)\n"
                 "  --baud N        every servo's Baud Rate item (default: 1000000 on the E-TRoll bus,\n"
                 "                  as configured at bring-up; 57600, the factory value, with --servo)\n"
                 "  --return-delay-us N  every servo's Return Delay Time (default: 0 on the E-TRoll bus,\n"
                 "                  as configured at bring-up; 500, the factory value, with --servo)\n"
                 "  --wire-baud N   delay replies as a real bus at N baud would; 'line' (default): at the\n"
                 "                  rate the client set on the port; 0: answer instantly\n"
                 "  --status-every  print every servo's state each SECONDS (default: off)\n"
                 "  --inject        a fault (repeatable): servo ID, AFTER_S seconds after the start, does\n"
                 "                  KIND: silent (stops answering), hardware-error (overload: alert bit,\n"
                 "                  Hardware Error Status, torque off), corrupt (bad CRC), slow (answers\n"
                 "                  0.5 s late)\n",
                 d.object_width_mm, d.hand.finger_offset_sum, d.hand.array_distance, d.palm_mm_per_degree,
                 d.palm_centre_mm);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    BusEmulator bus;
    std::vector<ServoSetup> servos;
    bool any = false;
    std::string link;
    PtyEmulatorOptions options;
    options.wire_baud_from_line = true;
    std::optional<std::uint8_t> baud_index;
    std::optional<std::uint8_t> return_delay;  // 2 µs units
    double status_every = 0;
    std::optional<bool> object_wanted;  // default: an object on the E-TRoll bus only
    ClampedObject geometry;
    std::vector<InjectedFault> faults;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
        if (a == "--help" || a == "-h") return usage(nullptr), 0;
        if (a == "--servo") {
            const char* v = value();
            if (!v) return usage("--servo needs a value");
            auto s = parse_servo_spec(v);
            if (!s.ok()) return usage(s.error().message.c_str());
            for (const auto& other : servos)
                if (other.id == s->id) return usage(("servo id " + std::to_string(s->id) + " given twice").c_str());
            servos.push_back(*s);
            any = true;
        } else if (a == "--link") {
            const char* v = value();
            if (!v) return usage("--link needs a path");
            link = v;
        } else if (a == "--object") {
            const char* v = value();
            if (!v) return usage("--object needs a width in mm or 'none'");
            object_wanted = std::string(v) != "none";
            if (*object_wanted && !positive_mm(v, geometry.object_width_mm))
                return usage(("--object: bad width '" + std::string(v) + "' (a positive number of mm, or none)").c_str());
        } else if (a == "--finger-offset-sum") {
            const char* v = value();
            if (!v || !positive_mm(v, geometry.hand.finger_offset_sum))
                return usage("--finger-offset-sum needs a positive length in mm");
        } else if (a == "--array-distance") {
            const char* v = value();
            if (!v || !positive_mm(v, geometry.hand.array_distance))
                return usage("--array-distance needs a positive length in mm");
        } else if (a == "--palm") {
            const char* v = value();
            char* end = nullptr;
            if (v) geometry.palm_mm_per_degree = std::strtod(v, &end);
            if (!v || *end != ':' || geometry.palm_mm_per_degree == 0)
                return usage("--palm needs MM_PER_DEG:CENTRE_MM, e.g. 0.349:65");
            const char* centre = end + 1;
            geometry.palm_centre_mm = std::strtod(centre, &end);
            if (*end != '\0' || end == centre) return usage("--palm needs MM_PER_DEG:CENTRE_MM, e.g. 0.349:65");
        } else if (a == "--baud") {
            const char* v = value();
            const auto index = v ? index_from_baud(static_cast<std::uint32_t>(std::strtoul(v, nullptr, 10)))
                                 : std::nullopt;
            if (!index) return usage("--baud needs a Dynamixel rate (9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000)");
            baud_index = *index;
        } else if (a == "--return-delay-us") {
            const char* v = value();
            char* end = nullptr;
            const long us = v ? std::strtol(v, &end, 10) : -1;
            if (!v || *end != '\0' || us < 0 || us > 508)
                return usage("--return-delay-us needs 0-508 (microseconds, in steps of 2)");
            return_delay = static_cast<std::uint8_t>(us / 2);
        } else if (a == "--wire-baud") {
            const char* v = value();
            if (!v) return usage("--wire-baud needs a rate, 'line' or 0");
            options.wire_baud_from_line = std::string(v) == "line";
            options.wire_baud = options.wire_baud_from_line ? 0 : static_cast<std::uint32_t>(std::strtoul(v, nullptr, 10));
        } else if (a == "--status-every") {
            const char* v = value();
            if (!v) return usage("--status-every needs seconds");
            status_every = std::strtod(v, nullptr);
        } else if (a == "--inject") {
            const char* v = value();
            if (!v) return usage("--inject needs ID:KIND:AFTER_S, e.g. 2:silent:1.5");
            auto f = parse_injected_fault(v);
            if (!f.ok()) return usage(("--inject: " + f.error().message).c_str());
            faults.push_back(*f);
        } else {
            return usage(("unknown argument '" + a + "'").c_str());
        }
    }
    if (!any) {
        servos = etroll_servos();
        if (!baud_index) baud_index = index_from_baud(1'000'000);
        if (!return_delay) return_delay = 0;
    }
    for (auto& s : servos) {
        if (baud_index) s.baud_index = *baud_index;
        if (return_delay) s.return_delay = *return_delay;
        bus.add_servo(s);
    }
    if (object_wanted.value_or(!any)) {
        if (auto st = rollsense::etroll::clamp_object(bus, geometry); !st.ok())
            return usage((st.message() + " (--object needs servos 1 sensing, 2 pushing and 3 palm)").c_str());
    }

    for (const auto& f : faults) {
        if (!bus.servo(f.id)) return usage(("--inject: no servo " + std::to_string(f.id) + " on this bus").c_str());
        bus.schedule(f);
    }

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
    // Only our own link: another emulator started meanwhile may have taken the name.
    if (!link.empty()) {
        std::error_code ec;
        if (std::filesystem::read_symlink(link, ec) == e.device()) ::unlink(link.c_str());
    }
    return 0;
}
