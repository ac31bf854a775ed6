// Timing of the control loop on a real clock: how regular the control periods are (jitter) and how much of each the
// bus exchange takes. Kept as fixed histograms (10 µs bins up to 250 ms) so a run of hours costs no more memory than
// a run of seconds. Only meaningful on the monotonic clock; on the virtual clock periods are exact by construction.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace rollsense::runtime {

class DurationHistogram {
public:
    void add(double seconds);
    std::uint64_t count() const { return count_; }
    // The q-quantile (0..1) in seconds, to the bin width; 0 when empty.
    double quantile(double q) const;
    double max() const { return max_; }

private:
    static constexpr double kBin = 10e-6;
    static constexpr std::size_t kBins = 25'000;
    std::array<std::uint32_t, kBins + 1> bins_{};  // last bin: overflow
    std::uint64_t count_ = 0;
    double max_ = 0.0;
};

struct LoopTimingSummary {
    double nominal_period_s = 0;
    std::uint64_t periods = 0;
    double period_p50_s = 0, period_p99_s = 0, period_max_s = 0;
    double jitter_p50_s = 0, jitter_p99_s = 0;  // |period - nominal|
    double busy_p50_s = 0, busy_p99_s = 0;      // read + controllers + write, per period
    // "period p50 10.00 ms, p99 10.21 ms, ..." for the terminal and run-info.csv.
    std::string describe() const;
};

class LoopTiming {
public:
    explicit LoopTiming(double nominal_period_s) : nominal_(nominal_period_s) {}
    // One control period: the time since the previous tick began, and how
    // long this tick's exchange with the devices took.
    void add(double period_s, double busy_s);
    LoopTimingSummary summary() const;

private:
    double nominal_;
    DurationHistogram period_, jitter_, busy_;
};

}  // namespace rollsense::runtime
