#include "cli/command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "rollsense/csv.hpp"

namespace rollsense::cli {
namespace {
std::vector<Command>& registry() {
    static std::vector<Command> list;
    return list;
}

// "--name=value" → ("--name", "value")
bool split_equals(const std::string& arg, std::string_view name, std::string* value) {
    if (arg.size() > name.size() && arg.compare(0, name.size(), name) == 0 && arg[name.size()] == '=') {
        if (value) *value = arg.substr(name.size() + 1);
        return true;
    }
    return false;
}

// Options whose every value names a folder that must exist, checked here, where
// every command parses them: a mistyped folder would otherwise be searched,
// found empty, and the run would go on with what the other folders hold.
constexpr std::string_view kFolderOptions[] = {"--plugin-path", "--training"};

void check_folder(std::string_view option, const std::string& value) {
    std::error_code ec;
    if (std::filesystem::is_directory(value, ec)) return;
    const bool exists = std::filesystem::exists(value, ec);
    throw UsageError(std::string(option) + " " + value + ": " + (exists ? "not a folder" : "no such folder") +
                     " (give an existing folder, or leave the option out)");
}
}  // namespace

Registration::Registration(Command command) { registry().push_back(std::move(command)); }

const std::vector<Command>& commands() { return registry(); }

int exit_code_for(ErrorCode code, int fallback) {
    switch (code) {
        case ErrorCode::ok: return kExitOk;
        case ErrorCode::cancelled: return kExitCancelled;
        case ErrorCode::bad_setting: return kExitUsage;
        case ErrorCode::io_error: return kExitIo;
        case ErrorCode::timeout:
        case ErrorCode::protocol_error:
        case ErrorCode::hardware_fault: return kExitHardware;
        case ErrorCode::not_found:
        case ErrorCode::parse_error:
        case ErrorCode::bad_profile:
        case ErrorCode::plugin_error: return kExitConfig;
        default: return fallback;
    }
}

std::string exit_code_table() {
    return "  0    ok\n"
           "  1    the job ran and failed (the script raised an error or named what the profile lacks, failed evaluation)\n"
           "  2    bad command line\n"
           "  3    bad profile, plugin or input file (a script that does not parse, an object the catalogue lacks)\n"
           "  4    a device failed or stopped answering (a joint that did not arrive within its move's timeout too)\n"
           "  5    a file could not be read or written (disk full, read-only, permission)\n"
           "  130  interrupted (Ctrl-C, emergency stop, --time-limit)\n";
}

bool Args::wants_help() const {
    for (const auto& a : args_)
        if (a == "--help" || a == "-h") return true;
    return false;
}

// Given twice, one of the two values would be dropped without a word (review: `submit.sh ... SCRIPT --out X` gave
// every shard's run two --out, and the first shard recorded the whole run into X).
std::string Args::option(std::string_view name, std::string_view short_name) const {
    auto all = options(name);
    if (!short_name.empty())
        for (auto& v : options(short_name)) all.push_back(std::move(v));
    if (all.size() > 1)
        throw UsageError("option " + std::string(name) + (short_name.empty() ? "" : " (" + std::string(short_name) + ")") +
                         " is given " + std::to_string(all.size()) + " times ('" + all[0] + "' and '" + all[1] +
                         "'): give it once");
    return all.empty() ? std::string() : all.back();
}

std::vector<std::string> Args::options(std::string_view name) const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < args_.size(); ++i) {
        std::string value;
        if (split_equals(args_[i], name, &value)) {
            out.push_back(value);
        } else if (args_[i] == name) {
            if (i + 1 >= args_.size()) throw UsageError("option " + std::string(name) + " needs a value");
            out.push_back(args_[++i]);
        }
    }
    // An empty value would read as the option left out (review: `--shard ''`, a batch script's unset variable,
    // recorded the whole run; `--seed ''` took the default seed).
    if (std::ranges::find(out, std::string()) != out.end())
        throw UsageError("option " + std::string(name) + " has an empty value (an unset shell variable?): give a value, "
                         "or leave the option out");
    if (std::find(std::begin(kFolderOptions), std::end(kFolderOptions), name) != std::end(kFolderOptions))
        for (const auto& folder : out) check_folder(name, folder);
    return out;
}

bool Args::flag(std::string_view name) const {
    bool given = false;
    for (const auto& a : args_) {
        given = given || a == name;
        // A switch takes no value (diff review: `run --check=yes`, read as no --check, ran the whole experiment).
        if (split_equals(a, name, nullptr))
            throw UsageError(std::string(name) + " takes no value: give it alone ('" + a + "' was given)");
    }
    return given;
}

bool Args::given(std::string_view name) const {
    return std::any_of(args_.begin(), args_.end(),
                       [&](const std::string& a) { return a == name || split_equals(a, name, nullptr); });
}

std::uint64_t Args::unsigned_option(std::string_view name, std::uint64_t fallback, std::uint64_t min,
                                    std::uint64_t max) const {
    const auto text = option(name);
    if (text.empty()) return fallback;
    auto v = csv::parse_unsigned(text, max, std::string(name));
    if (!v || *v < min)
        throw UsageError(std::string(name) + " expects a whole number from " + std::to_string(min) + " to " +
                         std::to_string(max) + ", got '" + text + "'");
    return *v;
}

double Args::number_option(std::string_view name, double fallback, double min, double max) const {
    const auto text = option(name);
    if (text.empty()) return fallback;
    auto v = csv::parse_number(text, std::string(name));
    if (!v || !std::isfinite(*v) || *v < min || *v > max)
        throw UsageError(std::string(name) + " expects a number from " + csv::format_number(min) + " to " +
                         csv::format_number(max) + ", got '" + text + "'");
    return *v;
}

std::vector<std::string> Args::positionals(const std::vector<std::string>& valued) const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < args_.size(); ++i) {
        const auto& a = args_[i];
        if (a.size() > 1 && a[0] == '-') {
            bool takes_value = false;
            for (const auto& v : valued) takes_value = takes_value || a == v;
            if (takes_value) ++i;
            continue;
        }
        out.push_back(a);
    }
    return out;
}

void Args::reject_unknown(const std::vector<std::string>& known) const {
    for (const auto& a : args_) {
        if (a.size() < 2 || a[0] != '-' || a == "-") continue;
        if (a == "--help" || a == "-h") continue;
        bool ok = false;
        for (const auto& k : known) ok = ok || a == k || split_equals(a, k, nullptr);
        // a negative number is a value, not an option
        if (!ok && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')) ok = true;
        if (!ok) throw UsageError("unknown option '" + a + "' (see --help)");
    }
}

}  // namespace rollsense::cli
