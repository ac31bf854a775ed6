#include "playback.hpp"

#include <algorithm>

namespace rollsense::plugins::replay {

Playback::Playback(const std::vector<double>& time, double nominal_period) {
    offsets_.reserve(time.size());
    for (double t : time) offsets_.push_back(t - time.front());
    // The mean spacing is the recording's own rate, also for a hand-made file
    // whose rate the dataset does not state.
    period_ = offsets_.size() >= 2 ? offsets_.back() / static_cast<double>(offsets_.size() - 1) : nominal_period;
    last_ = offsets_.size();
}

void Playback::start(double run_time) {
    start_ = run_time;
    reads_ = distinct_ = repeated_ = skipped_ = past_end_ = 0;
    last_ = offsets_.size();
}

Playback::Position Playback::locate(double run_time) {
    ++reads_;
    Position p;
    const double elapsed = run_time - start_;
    if (elapsed < -kTimeTolerance) {
        p.before_start = true;
        return p;
    }
    if (offsets_.empty() || elapsed >= duration() - kTimeTolerance) {
        p.past_end = true;
        ++past_end_;
        return p;
    }
    auto it = std::upper_bound(offsets_.begin(), offsets_.end(), elapsed + kTimeTolerance);
    p.index = it == offsets_.begin() ? 0 : static_cast<std::size_t>(it - offsets_.begin()) - 1;

    const bool first = last_ == offsets_.size();
    if (!first && p.index == last_) {
        ++repeated_;
    } else {
        ++distinct_;
        const std::size_t expected = first ? 0 : last_ + 1;
        if (p.index > expected) skipped_ += p.index - expected;
    }
    last_ = p.index;
    return p;
}

}  // namespace rollsense::plugins::replay
