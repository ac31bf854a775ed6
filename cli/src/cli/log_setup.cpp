#include "cli/log_setup.hpp"

#include <unistd.h>

#include <cstdio>

#include "rollsense/log.hpp"

namespace rollsense::cli {

void setup_logging(const Args& args) {
    if (args.flag("-v") || args.flag("--verbose"))
        set_log_level(LogLevel::debug);
    else if (args.flag("-q") || args.flag("--quiet"))
        set_log_level(LogLevel::warning);
    else
        set_log_level(LogLevel::info);
    const bool color = ::isatty(STDERR_FILENO) != 0;
    set_log_sink([color](LogLevel level, std::string_view source, std::string_view message) {
        const char* tint = "";
        if (color) tint = level == LogLevel::error ? "\033[31m" : level == LogLevel::warning ? "\033[33m" : "";
        std::fprintf(stderr, "%s%-7.*s\033[0m %.*s: %.*s\n", tint, static_cast<int>(to_string(level).size()),
                     to_string(level).data(), static_cast<int>(source.size()), source.data(),
                     static_cast<int>(message.size()), message.data());
    });
    if (!color)  // no escape codes in logs and pipes
        set_log_sink([](LogLevel level, std::string_view source, std::string_view message) {
            std::fprintf(stderr, "%-7.*s %.*s: %.*s\n", static_cast<int>(to_string(level).size()),
                         to_string(level).data(), static_cast<int>(source.size()), source.data(),
                         static_cast<int>(message.size()), message.data());
        });
}

}  // namespace rollsense::cli
