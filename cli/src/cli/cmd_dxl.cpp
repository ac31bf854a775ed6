// `rollsense dxl ...`: bring up a Dynamixel bus before any profile runs.
//   scan    which ids answer, at which baud rate, which model
//   info    one servo's identity, mode, limits, health and position
//   reboot  clear a latched hardware error
//   set-id / set-baud   give a fresh servo (they all ship as id 1, 57600) its place on the E-TRoll bus
// Works the same on /dev/ttyUSB0 and on the pty of `rollsense-dxl-emu`.
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "rollsense/hal/dynamixel/bus.hpp"
#include "rollsense/hal/serial_port.hpp"

namespace rollsense::cli {
namespace {

namespace dxl = hal::dxl;
using namespace std::chrono_literals;

const char* kHelp =
    "usage: rollsense dxl scan   --device PATH [--baud N | --all-bauds] [--ids FIRST-LAST] [--timeout-ms N]\n"
    "       rollsense dxl info   --device PATH [--baud N] --id N\n"
    "       rollsense dxl reboot --device PATH [--baud N] --id N\n"
    "       rollsense dxl set-id   --device PATH [--baud N] --id N --new-id M\n"
    "       rollsense dxl set-baud --device PATH [--baud N] --id N --new-baud RATE\n"
    "\n"
    "Talks Dynamixel Protocol 2.0 (X series) on a serial port or on the pty printed by rollsense-dxl-emu.\n"
    "  --device PATH    serial port, e.g. /dev/ttyUSB0 (U2D2) or /tmp/etroll-bus (emulator --link)\n"
    "  --baud N         bus rate, an X-series rate like --new-baud (default 57600, the factory setting)\n"
    "  --all-bauds      scan at every X-series rate (9600 ... 4.5M): finds servos at unknown rates\n"
    "  --ids A-B        id range to scan, A <= B (default 0-252)\n"
    "  --timeout-ms N   reply timeout per id while scanning (default 10)\n"
    "set-id and set-baud write EEPROM: they turn that servo's torque off first.\n"
    "Exit codes: 0 ok (scan: at least one servo found), 4 no answer / bus failure, 2 bad command line.";

struct Common {
    std::string device;
    std::uint32_t baud = 57600;
};

int parse_int(const std::string& text, const char* option, long lo, long hi) {
    try {
        std::size_t used = 0;
        const long v = std::stol(text, &used, 0);
        if (used != text.size() || v < lo || v > hi) throw std::out_of_range(text);
        return static_cast<int>(v);
    } catch (const std::exception&) {
        throw UsageError(std::string(option) + ": '" + text + "' is not a number in " + std::to_string(lo) + "-" +
                         std::to_string(hi));
    }
}

// A bus rate: one the X-series control table knows (baud_from_index), the list from there.
std::uint32_t parse_rate(const std::string& text, const char* option) {
    const auto rate = static_cast<std::uint32_t>(parse_int(text, option, 1, 4500000));
    if (dxl::index_from_baud(rate)) return rate;
    std::string rates;
    for (std::uint8_t i = 0; auto r = dxl::baud_from_index(i); ++i) rates += (i ? ", " : "") + std::to_string(*r);
    throw UsageError(std::string(option) + ": " + text + " is not an X-series rate (" + rates + ")");
}

Result<dxl::Bus> open_bus(const Common& c, std::chrono::microseconds timeout) {
    auto port = hal::SerialPort::open(c.device, c.baud);
    if (!port.ok()) return port.error();
    return dxl::Bus(std::move(port).value(), dxl::BusOptions{timeout, 2});
}

int fail(const Status& st) {
    std::fprintf(stderr, "rollsense dxl: %s\n", st.error().describe().c_str());
    return st.code() == ErrorCode::invalid_argument ? kExitUsage : kExitHardware;
}

std::string model_name(std::uint16_t number) {
    const auto* m = dxl::find_model(number);
    return m ? std::string(m->name) : "unknown model " + std::to_string(number);
}

int scan(const Common& c, const Args& args) {
    int first = 0, last = dxl::kMaxId;
    if (auto ids = args.option("--ids"); !ids.empty()) {
        const auto dash = ids.find('-');
        if (dash == std::string::npos) {
            first = last = parse_int(ids, "--ids", 0, dxl::kMaxId);
        } else {
            first = parse_int(ids.substr(0, dash), "--ids", 0, dxl::kMaxId);
            last = parse_int(ids.substr(dash + 1), "--ids", 0, dxl::kMaxId);
            if (last < first)
                throw UsageError("--ids " + ids + ": the range is reversed (FIRST-LAST, e.g. " + std::to_string(last) +
                                 "-" + std::to_string(first) + ")");
        }
    }
    const auto timeout_ms = args.option("--timeout-ms").empty() ? 10 : parse_int(args.option("--timeout-ms"), "--timeout-ms", 1, 1000);
    std::vector<std::uint32_t> rates{c.baud};
    if (args.flag("--all-bauds")) {
        rates.clear();
        for (std::uint8_t i = 0; i < 8; ++i) rates.push_back(*dxl::baud_from_index(i));
    }
    int found = 0;
    for (auto rate : rates) {
        Common at = c;
        at.baud = rate;
        auto bus = open_bus(at, std::chrono::milliseconds(timeout_ms));
        if (!bus.ok()) return fail(bus.status());
        std::printf("scanning %s at %u baud, ids %d-%d ...\n", c.device.c_str(), rate, first, last);
        std::fflush(stdout);
        auto replies = bus->scan(static_cast<std::uint8_t>(first), static_cast<std::uint8_t>(last),
                                 std::chrono::milliseconds(timeout_ms));
        if (!replies.ok()) return fail(replies.status());
        for (const auto& r : *replies) {
            std::printf("  id %3u  %-12s firmware %u%s\n", r.id, model_name(r.model_number).c_str(), r.firmware,
                        r.alert ? "  HARDWARE ERROR (rollsense dxl info / reboot)" : "");
            ++found;
        }
    }
    if (found == 0) {
        std::fprintf(stderr,
                     "rollsense dxl: no servo answered on %s; check power (the U2D2 does not power servos), "
                     "the cable, and the baud rate (try --all-bauds)\n",
                     c.device.c_str());
        return kExitHardware;
    }
    std::printf("%d servo(s) found\n", found);
    return kExitOk;
}

int info(const Common& c, int id) {
    auto bus = open_bus(c, 50ms);
    if (!bus.ok()) return fail(bus.status());
    const auto u8 = static_cast<std::uint8_t>(id);
    // One READ of the whole table (0..146) rather than a dozen small ones.
    auto table = bus->read(u8, 0, dxl::addr::table_size);
    if (!table.ok()) return fail(table.status());
    const auto& d = table->data;
    auto v = [&](std::uint16_t a, std::uint16_t size) { return dxl::get_le_signed(&d[a], size); };
    auto u = [&](std::uint16_t a, std::uint16_t size) { return dxl::get_le(&d[a], size); };
    const auto* model = dxl::find_model(static_cast<std::uint16_t>(u(dxl::addr::model_number, 2)));
    const auto mode = static_cast<dxl::OperatingMode>(u(dxl::addr::operating_mode, 1));
    const auto baud = dxl::baud_from_index(static_cast<std::uint8_t>(u(dxl::addr::baud_rate, 1)));
    std::printf("id %d: %s, firmware %u\n", id, model_name(static_cast<std::uint16_t>(u(dxl::addr::model_number, 2))).c_str(),
                u(dxl::addr::firmware_version, 1));
    std::printf("  baud rate        %u\n", baud ? *baud : 0u);
    std::printf("  operating mode   %s\n", dxl::to_string(mode).c_str());
    std::printf("  torque           %s\n", u(dxl::addr::torque_enable, 1) ? "on" : "off");
    // Address 98: a tripped watchdog (-1) makes the servo stop and ignore every goal until 98 is written 0, which
    // the next run's activation does (review: after a killed run this looked like a servo merely holding).
    const auto watchdog = v(dxl::addr::bus_watchdog, 1);
    std::printf("  bus watchdog     %s\n", watchdog < 0   ? "TRIPPED: stopped, ignores goals until a run activates it"
                                        : watchdog == 0 ? "off"
                                                        : (std::to_string(watchdog * 20) + " ms").c_str());
    std::printf("  position limits  %.2f .. %.2f deg (ticks %d .. %d)\n",
                dxl::ticks_to_degrees(v(dxl::addr::min_position_limit, 4)),
                dxl::ticks_to_degrees(v(dxl::addr::max_position_limit, 4)), v(dxl::addr::min_position_limit, 4),
                v(dxl::addr::max_position_limit, 4));
    if (model)
        std::printf("  current limit    %.0f mA\n", dxl::current_units_to_ma(*model, u(dxl::addr::current_limit, 2)));
    std::printf("  velocity limit   %.2f rev/min\n", dxl::velocity_units_to_rpm(u(dxl::addr::velocity_limit, 4)));
    std::printf("  present position %.2f deg (tick %d)\n", dxl::ticks_to_degrees(v(dxl::addr::present_position, 4)),
                v(dxl::addr::present_position, 4));
    std::printf("  input voltage    %.1f V\n", u(dxl::addr::present_input_voltage, 2) / 10.0);
    std::printf("  temperature      %u degC\n", u(dxl::addr::present_temperature, 1));
    const auto hw = static_cast<std::uint8_t>(u(dxl::addr::hardware_error_status, 1));
    std::printf("  hardware error   %s\n", hw ? (dxl::describe_hardware_error(hw) + " (rollsense dxl reboot --id " +
                                                  std::to_string(id) + " after removing the cause)").c_str()
                                              : "none");
    return kExitOk;
}

// What answers to `id`, if anything (the port is closed again after). Only a
// timeout shows the id is free: two servos that share it garble their replies.
std::optional<std::string> what_answers(const Common& c, std::uint8_t id) {
    auto bus = open_bus(c, 50ms);
    if (!bus.ok()) return std::nullopt;  // the caller's own open says why
    auto reply = bus->ping(id);
    if (reply.ok()) return "a " + model_name(reply->model_number);
    if (reply.error().code == ErrorCode::timeout) return std::nullopt;
    return "a reply that is not a servo's (" + reply.error().message + "; two servos sharing the id?)";
}

// `answers_after`, if given, settles a write whose status packet never came:
// a servo given a new id takes it as it executes the WRITE, so its reply may
// come from the new id, which a transaction addressed to the old one ignores.
int write_eeprom(const Common& c, int id, std::uint16_t address, int value, const std::string& what,
                 std::optional<std::uint8_t> answers_after = std::nullopt) {
    auto bus = open_bus(c, 50ms);
    if (!bus.ok()) return fail(bus.status());
    const auto u8 = static_cast<std::uint8_t>(id);
    if (auto st = bus->write_value(u8, dxl::addr::torque_enable, 1, 0); !st.ok()) return fail(st);
    if (auto st = bus->write_value(u8, address, 1, value); !st.ok())
        if (st.code() != ErrorCode::timeout || !answers_after || !bus->ping(*answers_after).ok()) return fail(st);
    std::printf("id %d: %s\n", id, what.c_str());
    return kExitOk;
}

int run_dxl(const std::vector<std::string>& raw) {
    Args args(raw);
    args.reject_unknown({"--device", "--baud", "--all-bauds", "--ids", "--timeout-ms", "--id", "--new-id", "--new-baud"});
    const auto pos = args.positionals({"--device", "--baud", "--ids", "--timeout-ms", "--id", "--new-id", "--new-baud"});
    const std::string actions = "scan, info, reboot, set-id, set-baud";
    if (pos.size() != 1) throw UsageError("expected one action (" + actions + ")");
    const std::string& action = pos[0];
    if ((", " + actions + ",").find(", " + action + ",") == std::string::npos)
        throw UsageError("unknown action '" + action + "' (" + actions + ")");
    Common c;
    c.device = args.option("--device");
    if (c.device.empty()) throw UsageError("--device is required (e.g. /dev/ttyUSB0, or the emulator's pty)");
    if (auto b = args.option("--baud"); !b.empty()) c.baud = parse_rate(b, "--baud");
    if (action == "scan") return scan(c, args);
    auto id_text = args.option("--id");
    if (id_text.empty()) throw UsageError(action + " needs --id N");
    const int id = parse_int(id_text, "--id", 0, dxl::kMaxId);
    if (action == "info") return info(c, id);
    if (action == "reboot") {
        auto bus = open_bus(c, 50ms);
        if (!bus.ok()) return fail(bus.status());
        if (auto st = bus->reboot(static_cast<std::uint8_t>(id)); !st.ok()) return fail(st);
        std::printf("id %d rebooted (torque is off; hardware error cleared)\n", id);
        return kExitOk;
    }
    if (action == "set-id") {
        const auto n = args.option("--new-id");
        if (n.empty()) throw UsageError("set-id needs --new-id M");
        const int new_id = parse_int(n, "--new-id", 0, dxl::kMaxId);
        if (new_id == id) throw UsageError("--new-id " + n + " is the servo's id already");
        // Two servos on one id answer together and garble each other's replies:
        // the new id must be free on this bus.
        if (auto taken = what_answers(c, static_cast<std::uint8_t>(new_id)))
            return fail({ErrorCode::invalid_argument,
                         "id " + n + " is taken: " + *taken + " on " + c.device +
                             " answers to it; give another --new-id (rollsense dxl scan lists the ids in use)"});
        return write_eeprom(c, id, dxl::addr::id, new_id, "id is now " + std::to_string(new_id),
                            static_cast<std::uint8_t>(new_id));
    }
    if (action == "set-baud") {
        const auto n = args.option("--new-baud");
        if (n.empty()) throw UsageError("set-baud needs --new-baud RATE");
        return write_eeprom(c, id, dxl::addr::baud_rate, *dxl::index_from_baud(parse_rate(n, "--new-baud")),
                            "baud rate is now " + n + " (talk to it with --baud " + n + ")");
    }
    return kExitUsage;  // not reached: the action was checked above
}

const Registration reg{{"dxl", "scan and set up a Dynamixel servo bus (or the emulator's pty)", kHelp, &run_dxl}};

}  // namespace
}  // namespace rollsense::cli
