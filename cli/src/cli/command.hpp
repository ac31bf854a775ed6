// Subcommands of the `rollsense` program. Each lives in its own
// cmd_<name>.cpp and registers itself at static-initialisation time:
//
//     static const rollsense::cli::Registration reg{{
//         "features", "extract the 13 features of a dataset",
//         "usage: rollsense features DATASET -o FILE [options]\n...", &run_features}};
//
// `run` receives the arguments after the subcommand name and returns the
// process exit code (see ExitCode).
#pragma once

#include <stdexcept>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::cli {

// Exit codes shared by every subcommand. exit_code_table() is the one text
// of them, printed by `rollsense --help` and copied into README.md (a test
// compares the two).
enum ExitCode : int {
    kExitOk = 0,
    kExitFailure = 1,      // the job ran and failed (a script error, a failed test of the data)
    kExitUsage = 2,        // bad command line
    kExitConfig = 3,       // a profile, plugin or input file is wrong
    kExitHardware = 4,     // a device failed or stopped answering
    kExitIo = 5,           // a file could not be read or written (disk full, read-only, permission)
    kExitCancelled = 130,  // interrupted (Ctrl-C, emergency stop, time limit)
};

// The exit code for a failed Status: io_error → kExitIo, device errors →
// kExitHardware, not_found/parse_error/bad_profile/plugin_error → kExitConfig, cancelled →
// kExitCancelled, bad_setting (a --set, --seed or --profile refused) → kExitUsage; any other code → `fallback` (the command knows best whether
// e.g. an invalid_argument came from its input file or from the job).
int exit_code_for(ErrorCode code, int fallback = kExitFailure);

// "code  meaning" lines, one per ExitCode.
std::string exit_code_table();

struct Command {
    std::string name;
    std::string summary;  // one line for the command list
    std::string help;     // full text for `rollsense <name> --help`
    int (*run)(const std::vector<std::string>& args);
    bool own_help = false;  // --help goes to `run` (run SCRIPT --help lists the script's settings)
};

struct Registration {
    explicit Registration(Command command);
};

const std::vector<Command>& commands();

// Small argument helpers so every command parses the same way.
class Args {
public:
    explicit Args(const std::vector<std::string>& args) : args_(args) {}
    // True if --help or -h is present.
    bool wants_help() const;
    // Value of "--name VALUE" or "--name=VALUE" (or of its `short_name`); empty if absent. Throws
    // UsageError if the option is present without a value, with an empty one, or more than once.
    std::string option(std::string_view name, std::string_view short_name = {}) const;
    // Every occurrence (an empty value throws UsageError). A folder option (--plugin-path, --training) is checked here for every
    // command: a value that is not an existing folder throws UsageError naming both.
    std::vector<std::string> options(std::string_view name) const;
    // A switch: "--name" given; "--name=VALUE" throws UsageError (a switch takes no value).
    bool flag(std::string_view name) const;
    // Whether "--name" appears at all, alone or with a value ("--name V", "--name=V").
    bool given(std::string_view name) const;
    // "--name N": a whole number in [min, max] (no sign, fraction or exponent),
    // or `fallback` when absent. Throws UsageError naming the option and range.
    std::uint64_t unsigned_option(std::string_view name, std::uint64_t fallback, std::uint64_t min,
                                  std::uint64_t max) const;
    // "--name X": a finite number in [min, max], or `fallback` when absent.
    double number_option(std::string_view name, double fallback, double min, double max) const;
    // Arguments that are neither options nor option values. `valued` lists
    // options that take a value (so their value is not mistaken for a positional).
    std::vector<std::string> positionals(const std::vector<std::string>& valued) const;
    // Error on any --option not in `known` (so a typo is not silently ignored).
    void reject_unknown(const std::vector<std::string>& known) const;

private:
    const std::vector<std::string>& args_;
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace rollsense::cli
