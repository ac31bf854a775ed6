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

ROLLSENSE_API void log(LogLevel level, std::string_view source, std::string_view message);
inline void log_debug(std::string_view src, std::string_view msg) { log(LogLevel::debug, src, msg); }
inline void log_info(std::string_view src, std::string_view msg) { log(LogLevel::info, src, msg); }
inline void log_warning(std::string_view src, std::string_view msg) { log(LogLevel::warning, src, msg); }
inline void log_error(std::string_view src, std::string_view msg) { log(LogLevel::error, src, msg); }

}  // namespace rollsense
