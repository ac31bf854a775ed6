// The contact's own clock, as a live run reads it: identification before the
// roll ends cuts its prefixes on it (learn/prefix_evaluation.hpp).
//
// The paper's rule is that timing is relative to the contact, never to the
// roll or the clock: a larger cylinder crosses the array faster, so absolute
// timing would name its diameter without sensing its shape (its features
// divide every duration by a channel's width for that reason). A prefix cut
// from record_start shows more of a contact that began earlier; one cut a
// fixed time after the contact began shows more of a contact that crosses
// faster. This clock counts time in a duration of the contact itself: the
// full width at half maximum of the first bump (one sensor's reading as the
// object passes over it), from its half-way rise. For a given bump both are
// scale-free: the same for it twice as high, twice as long for it twice as
// slow. Which bump starts the clock is decided by the series rule's touch
// threshold (min_amplitude), so a contact pressed much harder or softer can
// start it on another sensor.
#pragma once

#include <cstddef>
#include <optional>
#include <span>

#include "analysis/series/prepare.hpp"

namespace rollsense::series {

// Samples a channel's resting level is read from: the recording's first
// valid ones (the roll starts before the contact).
inline constexpr std::size_t kClockRestSamples = 3;
// A reading counts as fallen below half its bump's maximum only this far
// below it: a saved trial holds readings to 9 significant digits, and a
// quantised reading can sit exactly on the half level, so without it a live
// run and its saved trial could see the fall one sample apart.
inline constexpr double kClockHalfTolerance = 1e-6;

struct ContactClock {
    std::size_t channel = 0;  // position in `channels` of the bump's channel
    double zero = 0.0;        // fractional sample index where the bump rose through half its maximum
    double unit = 0.0;        // its full width at half maximum, in samples (> 0)
    std::size_t known_at = 0; // the sample that showed the fall: the clock is known once it is recorded
};

// The clock of `trial` on `channels` (indices into trial.channels), reading
// samples [0, settings.prefix) when a prefix is set: the first channel whose
// reading rises settings.min_amplitude or more above its resting level (the
// median of its first kClockRestSamples valid readings: the series rule's
// test of a touched sensor) and then falls back below half its maximum so far. nullopt until that has happened. Invalid samples are
// skipped. Causal: appending samples never changes a clock once found.
std::optional<ContactClock> contact_clock(const TrialData& trial, std::span<const std::size_t> channels,
                                          const SeriesSettings& settings);

// The share of a nominal roll of `units` clock units that a recording of
// `samples` samples has reached: (last sample − zero) ÷ (units × unit).
// Evaluation and a live run both cut with it (prefix_samples is its inverse).
double clock_progress(const ContactClock& clock, double units, std::size_t samples);

}  // namespace rollsense::series
