// Playback of one recorded trial in time: which recorded sample answers a read
// at a given moment of the run clock.
//
// Time zero of the playback is the moment the script starts recording, and the
// trial's first sample plays then (recorded trial files keep time relative to
// the recording's start; a hand-made file may start anywhere, its first sample
// is its zero). A read at elapsed time e serves the last recorded sample at or
// before e: a sample-and-hold that follows the run clock, virtual or real, and
// copes with a dataset recorded at another rate (samples are then repeated or
// skipped, and counted). The last sample is held for one sample period of the
// recording; a read after that is past the end.
#pragma once

#include <cstddef>
#include <vector>

namespace rollsense::plugins::replay {

// The virtual clock's 2^-20 s grid and the trial files' 1 µs rounding differ
// by less than 2 µs; 0.1 ms absorbs that (and a real clock waking a little
// early) while staying far below any sample period.
inline constexpr double kTimeTolerance = 1e-4;

class Playback {
public:
    struct Position {
        std::size_t index = 0;
        bool before_start = false;
        bool past_end = false;
    };

    Playback() = default;
    // `time` strictly increasing (the dataset reader checks it), not empty.
    // `nominal_period` is used when the trial has a single sample.
    Playback(const std::vector<double>& time, double nominal_period);

    // The recording starts at `run_time`: playback rewinds to the first sample.
    void start(double run_time);
    // The sample to serve at `run_time`; updates the counters below.
    Position locate(double run_time);

    std::size_t samples() const { return offsets_.size(); }
    double period() const { return period_; }
    double start_time() const { return start_; }
    double duration() const { return offsets_.empty() ? 0.0 : offsets_.back() + period_; }

    std::size_t reads() const { return reads_; }
    std::size_t distinct_served() const { return distinct_; }
    std::size_t repeated() const { return repeated_; }   // reads that served the previous read's sample again
    std::size_t skipped() const { return skipped_; }     // recorded samples no read served (jumped over)
    std::size_t past_end() const { return past_end_; }   // reads after the recording's end
    // Index of the last sample served, or samples() when none was.
    std::size_t last_index() const { return last_; }

private:
    std::vector<double> offsets_;  // time of each sample since the first
    double period_ = 0.0;
    double start_ = 0.0;
    std::size_t reads_ = 0, distinct_ = 0, repeated_ = 0, skipped_ = 0, past_end_ = 0;
    std::size_t last_ = 0;
};

}  // namespace rollsense::plugins::replay
