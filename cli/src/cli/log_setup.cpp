#include "cli/log_setup.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

#include "rollsense/log.hpp"

namespace rollsense::cli {

void setup_logging(const Args& args) {
    if (args.flag("-v") || args.flag("--verbose"))
        set_log_level(LogLevel::debug);
    else if (args.flag("-q") || args.flag("--quiet"))
        set_log_level(LogLevel::warning);
    else
        set_log_level(LogLevel::info);
    // Decided once: colour only on a terminal that wants it, so pipes, log
    // files and NO_COLOR users never see escape codes.
    const bool colour = colour_allowed(STDERR_FILENO);
    set_log_sink([colour](LogLevel level, std::string_view source, std::string_view message) {
        const char* tint = "";
        if (colour) tint = level == LogLevel::error ? "\033[31m" : level == LogLevel::warning ? "\033[33m" : "";
        const char* reset = *tint ? "\033[0m" : "";
        const std::string stamp = log_time() ? log_timestamp() + " " : std::string();
        std::fprintf(stderr, "%s%s%-7.*s%s %.*s: %.*s\n", stamp.c_str(), tint,
                     static_cast<int>(to_string(level).size()), to_string(level).data(), reset,
                     static_cast<int>(source.size()), source.data(), static_cast<int>(message.size()),
                     message.data());
    });
}

}  // namespace rollsense::cli
