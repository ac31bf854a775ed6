// rollsense: the command-line program. Dispatches to the registered subcommands.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "rollsense/status.hpp"

namespace {

void print_overview() {
    std::printf(
        "rollsense %s — tactile object identification by rolling\n\n"
        "usage: rollsense <command> [options]     rollsense <command> --help\n\ncommands:\n",
        ROLLSENSE_VERSION_STRING);
    for (const auto& c : rollsense::cli::commands()) std::printf("  %-10s %s\n", c.name.c_str(), c.summary.c_str());
    std::printf(
        "\nexit codes: 0 ok, 1 the job failed, 2 bad command line, 3 bad profile/plugin/input file,\n"
        "            4 hardware failure, 130 interrupted (Ctrl-C or emergency stop)\n");
}

}  // namespace

int main(int argc, char** argv) {
    using namespace rollsense::cli;
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        print_overview();
        return args.empty() ? kExitUsage : kExitOk;
    }
    if (args[0] == "--version") {
        std::printf("rollsense %s\n", ROLLSENSE_VERSION_STRING);
        return kExitOk;
    }
    for (const auto& c : commands()) {
        if (c.name != args[0]) continue;
        std::vector<std::string> rest(args.begin() + 1, args.end());
        try {
            if (Args(rest).wants_help()) {
                std::printf("%s\n", c.help.c_str());
                return kExitOk;
            }
            return c.run(rest);
        } catch (const UsageError& e) {
            std::fprintf(stderr, "rollsense %s: %s\n", c.name.c_str(), e.what());
            return kExitUsage;
        } catch (const rollsense::StatusError& e) {
            std::fprintf(stderr, "rollsense %s: %s\n", c.name.c_str(), e.what());
            return kExitFailure;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "rollsense %s: unexpected error: %s\n", c.name.c_str(), e.what());
            return kExitFailure;
        }
    }
    std::fprintf(stderr, "rollsense: unknown command '%s' (run 'rollsense --help' for the list)\n", args[0].c_str());
    return kExitUsage;
}
