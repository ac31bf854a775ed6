// bench_dynamixel_bus [--baud N] [--periods N] [--return-delay-us N]
//
// Prints the time one control period spends on the bus: the dynamixel
// plugin's write() (one SYNC_WRITE of Goal Current..Goal Position, 18 bytes per
// servo) plus read() (one SYNC_READ of Moving..Present Position, 14 bytes per
// servo) for the E-TRoll's 4 servos, over a real pty to the emulator.
//   paced:   the emulator holds each reply back for its wire time at --baud
//            plus the Return Delay Time, so the figure is what a real bus costs
//            plus this machine's scheduling;
//   unpaced: bytes cross the pty instantly: the software overhead alone.
// The wire-time figure is computed from the packet sizes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dynamixel_actuator.hpp"
#include "rollsense/hal/dynamixel/emulator_config.hpp"
#include "rollsense/hal/dynamixel/pty_emulator.hpp"

using namespace rollsense;
using namespace rollsense::hal::dxl;

namespace {

struct Figures {
    double mean, p50, p95, max;
};

Figures summarise(std::vector<double> us) {
    std::sort(us.begin(), us.end());
    double sum = 0;
    for (double v : us) sum += v;
    return {sum / static_cast<double>(us.size()), us[us.size() / 2], us[us.size() * 95 / 100], us.back()};
}

Figures run(std::uint32_t baud, int periods, int return_delay_us, bool paced) {
    BusEmulator bus;
    for (auto s : etroll_servos()) {
        s.baud_index = *index_from_baud(baud);
        bus.add_servo(s);
    }
    for (auto id : bus.ids()) {
        Bytes d{static_cast<std::uint8_t>(return_delay_us / 2)};
        (void)bus.servo(id)->write(addr::return_delay_time, d);
    }
    auto emu = PtyBusEmulator::start(std::move(bus), {true, paced ? baud : 0});
    if (!emu.ok()) {
        std::fprintf(stderr, "bench: %s\n", emu.error().message.c_str());
        std::exit(4);
    }
    std::map<std::string, ParamValue> raw{
        {"device", (*emu)->device()},
        {"baud", std::int64_t{baud}},
        {"ids", std::vector<std::int64_t>{1, 2, 3, 4}},
        {"names", std::vector<std::string>{"sensing_finger", "pushing_finger", "palm", "winch"}},
        {"models", std::vector<std::string>{"XM430-W350", "XM430-W350", "XM430-W350", "XL330-M288"}},
        {"units", std::vector<std::string>{"deg", "deg", "mm", "mm"}},
        {"modes", std::vector<std::string>{"position", "position", "position", "extended_position"}},
        {"radius", std::vector<double>{0, 0, 10, 8}},
        {"ratio", std::vector<double>{1, 1, 2, 1}},
        {"offsets", std::vector<double>{0, 0, 65, 0}},
        {"min", std::vector<double>{-90, -90, 30, -500}},
        {"max", std::vector<double>{90, 90, 100, 500}},
        {"timeout_ms", std::int64_t{200}},
    };
    auto params = validate_params(dynamixel::dynamixel_schema(), raw, "bench");
    dynamixel::DynamixelActuator a;
    if (auto st = a.on_configure(*params, {}); !st.ok()) { std::fprintf(stderr, "bench: %s\n", st.message().c_str()); std::exit(4); }
    if (auto st = a.on_activate(); !st.ok()) { std::fprintf(stderr, "bench: %s\n", st.message().c_str()); std::exit(4); }
    std::vector<JointState> s(4);
    (void)a.read(0, s);
    std::vector<JointCommand> c(4);
    for (std::size_t i = 0; i < 4; ++i) {
        c[i].mode = a.joints()[i].modes.front();
        c[i].position = s[i].position;
        c[i].profile_velocity = 13.74;
    }
    std::vector<double> us;
    for (int p = 0; p < periods; ++p) {
        c[0].position = s[0].position + ((p % 2) ? 0.5 : -0.5);  // a goal that changes every period
        const auto t0 = std::chrono::steady_clock::now();
        if (auto st = a.write(0, c); !st.ok()) { std::fprintf(stderr, "bench: %s\n", st.message().c_str()); std::exit(4); }
        if (auto st = a.read(0, s); !st.ok()) { std::fprintf(stderr, "bench: %s\n", st.message().c_str()); std::exit(4); }
        us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    }
    (void)a.on_deactivate();
    return summarise(us);
}

}  // namespace

int main(int argc, char** argv) {
    std::uint32_t baud = 57600;
    int periods = 200, return_delay_us = 500;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--baud") baud = static_cast<std::uint32_t>(std::strtoul(argv[i + 1], nullptr, 10));
        else if (a == "--periods") periods = std::atoi(argv[i + 1]);
        else if (a == "--return-delay-us") return_delay_us = std::atoi(argv[i + 1]);
        else { std::fprintf(stderr, "usage: bench_dynamixel_bus [--baud N] [--periods N] [--return-delay-us N]\n"); return 2; }
    }
    if (!index_from_baud(baud)) { std::fprintf(stderr, "bench: %u is not an X-series baud rate\n", baud); return 2; }
    // Packet sizes on the wire: header+id+len (7), instruction (1), params, CRC (2).
    const std::size_t n = 4;
    const std::size_t sync_write = 7 + 1 + 4 + n * (1 + kCommandBlockLength) + 2;
    const std::size_t sync_read = 7 + 1 + 4 + n + 2;
    const std::size_t status = 7 + 1 + 1 + kStateBlockLength + 2;
    const double byte_us = 10.0 * 1e6 / baud;
    const double wire = static_cast<double>(sync_write + sync_read + n * status) * byte_us + n * return_delay_us;
    std::printf("E-TRoll bus, 4 servos, %u baud, return delay %d us, %d periods\n", baud, return_delay_us, periods);
    std::printf("  bytes per period: SYNC_WRITE %zu + SYNC_READ %zu + 4 status x %zu = %zu\n", sync_write, sync_read,
                status, sync_write + sync_read + n * status);
    std::printf("  wire time (computed):       %8.0f us  -> max control rate %.0f Hz\n", wire, 1e6 / wire);
    for (bool paced : {true, false}) {
        const auto f = run(baud, periods, return_delay_us, paced);
        std::printf("  %-8s over pty: mean %8.0f us  p50 %8.0f  p95 %8.0f  max %8.0f\n", paced ? "paced" : "unpaced",
                    f.mean, f.p50, f.p95, f.max);
    }
    return 0;
}
