// What a test checks was (or was not) logged.
#pragma once

#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "rollsense/log.hpp"

namespace rollsense::testing {

// Captures log messages (warnings and up by default) while alive.
class LogCapture {
public:
    explicit LogCapture(LogLevel min = LogLevel::warning) : min_(min) {
        old_level_ = log_level();
        set_log_level(LogLevel::debug);
        old_ = set_log_sink([this](LogLevel level, std::string_view src, std::string_view msg) {
            if (level < min_) return;
            std::lock_guard<std::mutex> lock(mutex_);
            lines_.push_back(std::string(to_string(level)) + " " + std::string(src) + ": " + std::string(msg));
        });
    }
    ~LogCapture() {
        set_log_sink(old_);
        set_log_level(old_level_);
    }
    std::vector<std::string> lines() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return lines_;
    }
    std::size_t count(const std::string& needle) const {
        std::size_t n = 0;
        for (const auto& l : lines())
            if (l.find(needle) != std::string::npos) ++n;
        return n;
    }
    std::string all() const {
        std::string out;
        for (const auto& l : lines()) out += l + "\n";
        return out;
    }

private:
    LogLevel min_;
    LogLevel old_level_ = LogLevel::info;
    LogSink old_;
    mutable std::mutex mutex_;
    std::vector<std::string> lines_;
};

}  // namespace rollsense::testing
