#include "rollsense/log.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <mutex>

namespace rollsense {
namespace {

std::atomic<bool> with_time{false};

void default_sink(LogLevel level, std::string_view source, std::string_view message) {
    const std::string stamp = with_time.load() ? log_timestamp() + " " : std::string();
    std::fprintf(stderr, "%s[%.*s] %.*s: %.*s\n", stamp.c_str(), static_cast<int>(to_string(level).size()),
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

void set_log_time(bool on) { with_time.store(on); }
bool log_time() { return with_time.load(); }

std::string log_timestamp() {
    const auto now = std::chrono::system_clock::now();
    const std::time_t t = std::chrono::system_clock::to_time_t(now);
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
    std::tm utc{};
    ::gmtime_r(&t, &utc);
    char buf[40];
    const std::size_t n = std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &utc);
    std::snprintf(buf + n, sizeof buf - n, ".%03dZ", static_cast<int>(ms));
    return buf;
}

bool colour_allowed(int fd) {
    if (::isatty(fd) == 0) return false;
    const char* no_color = std::getenv("NO_COLOR");
    if (no_color && *no_color) return false;
    const char* term = std::getenv("TERM");
    return !(term && std::strcmp(term, "dumb") == 0);
}

void log(LogLevel level, std::string_view source, std::string_view message) {
    if (static_cast<int>(level) < min_level.load()) return;
    std::lock_guard lock(sink_mutex);
    sink()(level, source, message);
}

}  // namespace rollsense
