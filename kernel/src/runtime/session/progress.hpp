// A progress line for long runs: trials done of total and the time left,
// estimated from wall time (simulation) or robot time (hardware, where they are
// the same clock). Quiet when stderr is not a terminal (CI, pipes, logs).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace rollsense::runtime {

class Progress {
public:
    explicit Progress(bool enabled);
    ~Progress();
    void update(std::size_t done, std::size_t total, const std::string& label, double run_clock_s);
    void finish();
    bool active() const { return enabled_; }

private:
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_{};
    std::size_t first_done_ = SIZE_MAX;
};

}  // namespace rollsense::runtime
