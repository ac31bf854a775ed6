// Levelled logging for the kernel, the HAL and plugins. The kernel installs the
// sink (terminal, with levels and the component's name); everyone else just logs.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "rollsense/export.hpp"

namespace rollsense {

enum class LogLevel { debug = 0, info = 1, warning = 2, error = 3 };

std::string_view to_string(LogLevel level) noexcept;

using LogSink = std::function<void(LogLevel, std::string_view source, std::string_view message)>;

// Replace the process-wide sink; returns the previous one. Thread-safe.
ROLLSENSE_API LogSink set_log_sink(LogSink sink);
// Messages below this level are dropped before formatting reaches the sink.
ROLLSENSE_API void set_log_level(LogLevel level);
ROLLSENSE_API LogLevel log_level();

// Whether sinks start each line with the wall-clock time (`--log-time`); off
// by default so that logs of deterministic runs compare equal.
ROLLSENSE_API void set_log_time(bool on);
ROLLSENSE_API bool log_time();
// Now as "2026-11-24T23:59:01.123Z" (UTC, milliseconds): sortable, and
// unambiguous across time zones and daylight saving.
ROLLSENSE_API std::string log_timestamp();

// Whether output to `fd` may carry ANSI colour: a terminal, NO_COLOR unset or
// empty (https://no-color.org) and TERM not "dumb".
ROLLSENSE_API bool colour_allowed(int fd);

ROLLSENSE_API void log(LogLevel level, std::string_view source, std::string_view message);
inline void log_debug(std::string_view src, std::string_view msg) { log(LogLevel::debug, src, msg); }
inline void log_info(std::string_view src, std::string_view msg) { log(LogLevel::info, src, msg); }
inline void log_warning(std::string_view src, std::string_view msg) { log(LogLevel::warning, src, msg); }
inline void log_error(std::string_view src, std::string_view msg) { log(LogLevel::error, src, msg); }

}  // namespace rollsense
