#include "rollsense/log.hpp"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace rollsense {
namespace {

void default_sink(LogLevel level, std::string_view source, std::string_view message) {
    std::fprintf(stderr, "[%.*s] %.*s: %.*s\n", static_cast<int>(to_string(level).size()),
                 to_string(level).data(), static_cast<int>(source.size()), source.data(),
                 static_cast<int>(message.size()), message.data());
}

std::mutex sink_mutex;
LogSink& sink() {
    static LogSink s = default_sink;
    return s;
}
std::atomic<int> min_level{static_cast<int>(LogLevel::info)};

}  // namespace

std::string_view to_string(LogLevel level) noexcept {
    switch (level) {
        case LogLevel::debug: return "debug";
        case LogLevel::info: return "info";
        case LogLevel::warning: return "warning";
        case LogLevel::error: return "error";
    }
    return "?";
}

LogSink set_log_sink(LogSink new_sink) {
    std::lock_guard lock(sink_mutex);
    LogSink old = std::move(sink());
    sink() = new_sink ? std::move(new_sink) : LogSink(default_sink);
    return old;
}

void set_log_level(LogLevel level) { min_level.store(static_cast<int>(level)); }
LogLevel log_level() { return static_cast<LogLevel>(min_level.load()); }

void log(LogLevel level, std::string_view source, std::string_view message) {
    if (static_cast<int>(level) < min_level.load()) return;
    std::lock_guard lock(sink_mutex);
    sink()(level, source, message);
}

}  // namespace rollsense
