#include "cli/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace rollsense::cli {

ProgressBar::ProgressBar(bool wanted)
    : enabled_(wanted && ::isatty(STDERR_FILENO)) {
    if (!enabled_) return;
    // Made before the run and the live view start their threads: nothing logs until log_sink_ is set. The lock
    // spans the line, so that the bar is not drawn between its newline and the log line (review).
    log_sink_ = set_log_sink([this](LogLevel level, std::string_view source, std::string_view message) {
        std::lock_guard lock(mutex_);
        end_line();
        log_sink_(level, source, message);
    });
}

ProgressBar::~ProgressBar() {
    if (!enabled_) return;
    set_log_sink(log_sink_);
    finish();
}

void ProgressBar::update(std::size_t done, std::size_t total, const std::string& label, double run_clock_s) {
    if (!enabled_ || total == 0) return;
    std::lock_guard lock(mutex_);
    auto now = std::chrono::steady_clock::now();
    // The rate counts from the first report on: not the setup before it, nor trials skipped on --resume.
    if (first_done_ == SIZE_MAX) first_done_ = done, start_ = now;
    if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const std::size_t fresh = done - first_done_;
    const double per = fresh > 0 ? elapsed / static_cast<double>(fresh) : 0.0;
    const double left = per * static_cast<double>(total - done);
    const int width = 30;
    const int filled = static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total));
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %zu/%zu %-18.18s robot %6.0f s  left %s%5.0f s ", bar.c_str(), done, total,
                 label.c_str(), run_clock_s, fresh > 0 ? "" : "~", left);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::finish() {
    std::lock_guard lock(mutex_);
    end_line();
}

void ProgressBar::end_line() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
}

}  // namespace rollsense::cli
