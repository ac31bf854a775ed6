#include "rollsense/features/peak.hpp"

namespace rollsense::features {

Peak find_peak(std::span<const double> x, double fraction) {
    Peak p;
    if (x.empty()) return p;
    // The running maximum in a register rather than re-reading x[imax]; strict >
    // keeps the first occurrence (and a NaN never replaces it).
    std::size_t imax = 0;
    double max = x[0];
    for (std::size_t i = 1; i < x.size(); ++i)
        if (x[i] > max) {
            max = x[i];
            imax = i;
        }
    p.max_index = imax;
    p.max = max;
    const double threshold = fraction * p.max;
    // Walk out from the maximum; the peak is everything still ≥ the threshold.
    std::size_t first = imax;
    while (first > 0 && x[first - 1] >= threshold) --first;
    std::size_t last = imax;
    while (last + 1 < x.size() && x[last + 1] >= threshold) ++last;
    p.first = first;
    p.last = last;
    p.closed_start = first > 0;
    p.closed_end = last + 1 < x.size();
    return p;
}

}  // namespace rollsense::features
