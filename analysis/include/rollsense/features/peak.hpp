// Peak extraction as the paper defines it: start at the maximum, walk outwards
// until the reading drops below a fraction (5 %) of the maximum.
#pragma once

#include <cstddef>
#include <span>

namespace rollsense::features {

struct Peak {
    std::size_t max_index = 0;  // first sample holding the maximum
    std::size_t first = 0;      // first sample of the peak (reading ≥ fraction · max)
    std::size_t last = 0;       // last sample of the peak
    double max = 0.0;
    // True when the walk found a sample below the threshold before running off
    // the series on that side: the object really left the sensor. A peak cut
    // off by the start or the end of the recording is incomplete.
    bool closed_start = false;
    bool closed_end = false;

    bool complete() const { return closed_start && closed_end; }
};

// Empty input gives a default Peak (max 0, not complete). The maximum is the
// first occurrence of the largest value.
Peak find_peak(std::span<const double> x, double fraction);

}  // namespace rollsense::features
