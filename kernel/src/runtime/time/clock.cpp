#include "runtime/time/clock.hpp"

#include <cerrno>
#include <cmath>
#include <ctime>

namespace rollsense::runtime {
namespace {
double monotonic_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}
}  // namespace

double Clock::quantize(double t) const {
    constexpr double kGrid = 1048576.0;  // 2^20 steps per second
    return is_virtual() ? std::round(t * kGrid) / kGrid : t;
}

MonotonicClock::MonotonicClock() : origin_(monotonic_seconds()) {}

double MonotonicClock::now() const { return monotonic_seconds() - origin_; }

void MonotonicClock::sleep_until(double t) {
    const double target = origin_ + t;
    timespec ts{};
    ts.tv_sec = static_cast<time_t>(std::floor(target));
    ts.tv_nsec = static_cast<long>((target - std::floor(target)) * 1e9);
    // Absolute deadline: no drift accumulates across periods.
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
}

std::unique_ptr<Clock> make_clock(bool virtual_time) {
    if (virtual_time) return std::make_unique<VirtualClock>();
    return std::make_unique<MonotonicClock>();
}

}  // namespace rollsense::runtime
