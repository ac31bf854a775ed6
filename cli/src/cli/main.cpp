// rollsense: the command-line program. Dispatches to the registered subcommands.
//
// Errors: a command either prints its error itself and returns an exit code,
// or throws; main prints a thrown error once, here, and maps it to the exit
// code of exit_code_table().
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "rollsense/log.hpp"
#include "rollsense/status.hpp"

namespace {

using namespace rollsense::cli;

void print_overview() {
    std::printf(
        "rollsense %s — tactile object identification by rolling\n\n"
        "usage: rollsense [--log-time] <command> [options]\n"
        "       rollsense <command> --help   (or: rollsense help <command>)\n"
        "       rollsense --version\n\ncommands:\n",
        ROLLSENSE_VERSION_STRING);
    for (const auto& c : commands()) std::printf("  %-10s %s\n", c.name.c_str(), c.summary.c_str());
    std::printf(
        "\nglobal options (before or after the command):\n"
        "  --log-time   start every log line with its UTC wall-clock time\n"
        "\nenvironment:\n"
        "  NO_COLOR     set and not empty: no colour in log lines (also off when stderr is not a terminal)\n"
        "\nexit codes:\n%s",
        exit_code_table().c_str());
}

void print_command_help(const Command& c) {
    std::printf("%s\n\nexit codes (rollsense --help):\n%s", c.help.c_str(), exit_code_table().c_str());
}

const Command* find_command(const std::string& name) {
    for (const auto& c : commands())
        if (c.name == name) return &c;
    return nullptr;
}

int unknown_command(const std::string& name) {
    std::fprintf(stderr, "rollsense: unknown command '%s' (run 'rollsense --help' for the list)\n", name.c_str());
    return kExitUsage;
}

// Runs one command; every exception that escapes it is printed here, once.
int dispatch(const Command& c, const std::vector<std::string>& rest) {
    try {
        if (!c.own_help && Args(rest).wants_help()) {
            print_command_help(c);
            return kExitOk;
        }
        return c.run(rest);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "rollsense %s: %s\n", c.name.c_str(), e.what());
        return kExitUsage;
    } catch (const rollsense::StatusError& e) {
        std::fprintf(stderr, "rollsense %s: %s\n", c.name.c_str(), e.what());
        return exit_code_for(e.status().code());
    } catch (const std::filesystem::filesystem_error& e) {
        std::fprintf(stderr, "rollsense %s: %s\n", c.name.c_str(), e.what());
        return kExitIo;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "rollsense %s: out of memory\n", c.name.c_str());
        return kExitFailure;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rollsense %s: unexpected error: %s\n", c.name.c_str(), e.what());
        return kExitFailure;
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args;
    // Global options are taken out wherever they stand, so each command's
    // option check never sees them.
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--log-time")
            rollsense::set_log_time(true);
        else
            args.push_back(a);
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
        print_overview();
        return args.empty() ? kExitUsage : kExitOk;
    }
    if (args[0] == "--version") {
        std::printf("rollsense %s\n", ROLLSENSE_VERSION_STRING);
        return kExitOk;
    }
    if (args[0] == "help") {  // `rollsense help CMD` is `rollsense CMD --help`
        if (args.size() == 1) {
            print_overview();
            return kExitOk;
        }
        if (args.size() > 2) {
            std::fprintf(stderr, "rollsense help: expects one command name, got %zu words\n", args.size() - 1);
            return kExitUsage;
        }
        const Command* c = find_command(args[1]);
        if (!c) return unknown_command(args[1]);
        print_command_help(*c);
        return kExitOk;
    }
    const Command* c = find_command(args[0]);
    if (!c) return unknown_command(args[0]);
    return dispatch(*c, std::vector<std::string>(args.begin() + 1, args.end()));
}
