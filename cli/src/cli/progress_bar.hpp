// `rollsense run`'s progress line for long runs: trials done of total and the
// time left, estimated from wall time (simulation) or robot time (hardware,
// where they are the same clock). Quiet when stderr is not a terminal (CI,
// pipes, logs). A log line while the bar is drawn starts on a line of its own.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

#include "rollsense/log.hpp"

namespace rollsense::cli {

class ProgressBar {
public:
    explicit ProgressBar(bool wanted);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;
    // From rs.progress, on the script's thread.
    void update(std::size_t done, std::size_t total, const std::string& label, double run_clock_s);
    // Ends the bar's line (before a log line, and when the run ends).
    void finish();

private:
    void end_line();  // with mutex_ held

    bool enabled_;
    LogSink log_sink_;  // the one the bar wraps, restored by the destructor
    std::mutex mutex_;  // log lines come from other threads too
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_;  // of the first update
    std::chrono::steady_clock::time_point last_draw_{};
    std::size_t first_done_ = SIZE_MAX;
};

}  // namespace rollsense::cli
