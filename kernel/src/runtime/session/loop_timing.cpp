#include "runtime/session/loop_timing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rollsense::runtime {

void DurationHistogram::add(double seconds) {
    if (!(seconds >= 0.0)) seconds = 0.0;
    const auto bin = static_cast<std::size_t>(std::min(seconds / kBin, static_cast<double>(kBins)));
    ++bins_[bin];
    ++count_;
    max_ = std::max(max_, seconds);
}

double DurationHistogram::quantile(double q) const {
    if (count_ == 0) return 0.0;
    // The smallest bin whose cumulative count reaches q of all samples,
    // reported at the bin's centre (the overflow bin reports the maximum).
    const auto rank = static_cast<std::uint64_t>(std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(count_)));
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < bins_.size(); ++i) {
        seen += bins_[i];
        if (seen >= std::max<std::uint64_t>(rank, 1))
            return i == kBins ? max_ : std::min(max_, (static_cast<double>(i) + 0.5) * kBin);
    }
    return max_;
}

void LoopTiming::add(double period_s, double busy_s) {
    period_.add(period_s);
    jitter_.add(std::abs(period_s - nominal_));
    busy_.add(busy_s);
}

LoopTimingSummary LoopTiming::summary() const {
    LoopTimingSummary s;
    s.nominal_period_s = nominal_;
    s.periods = period_.count();
    s.period_p50_s = period_.quantile(0.5);
    s.period_p99_s = period_.quantile(0.99);
    s.period_max_s = period_.max();
    s.jitter_p50_s = jitter_.quantile(0.5);
    s.jitter_p99_s = jitter_.quantile(0.99);
    s.busy_p50_s = busy_.quantile(0.5);
    s.busy_p99_s = busy_.quantile(0.99);
    return s;
}

std::string LoopTimingSummary::describe() const {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "%.0f Hz over %llu periods: period p50 %.2f ms, p99 %.2f ms, max %.2f ms (jitter p50 %.3f ms, "
                  "p99 %.3f ms); bus time per period p50 %.2f ms, p99 %.2f ms",
                  nominal_period_s > 0 ? 1.0 / nominal_period_s : 0.0, static_cast<unsigned long long>(periods),
                  period_p50_s * 1e3, period_p99_s * 1e3, period_max_s * 1e3, jitter_p50_s * 1e3,
                  jitter_p99_s * 1e3, busy_p50_s * 1e3, busy_p99_s * 1e3);
    return buf;
}

}  // namespace rollsense::runtime
