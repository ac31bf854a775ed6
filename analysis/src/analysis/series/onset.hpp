// The contact's own clock, as a live run reads it: when the object first
// presses the array (the onset), and how long the first sensor it presses
// takes to be passed (the unit), both found from the samples up to them only.
//
// Identification before the roll ends cuts its prefixes on this clock, so
// that timing is relative to the contact, as the paper's rule asks, in both
// senses: time zero is the onset (never record_start: when the object touches,
// relative to the roll's start, depends on where it sits and how large it is),
// and time is counted in the unit (never in seconds or samples: a contact that
// crosses the array faster would show more of itself by a fixed time, and the
// crossing speed names a cylinder's diameter without sensing its shape; the
// paper's features divide every duration by a channel's width for the same
// reason).
#pragma once

#include <cstddef>
#include <optional>
#include <span>

#include "analysis/series/prepare.hpp"

namespace rollsense::series {

// Samples a channel's resting level is read from: the recording's first
// valid ones (the roll starts before the contact; a trial already in contact
// at its first sample is one the series rule refuses anyway).
inline constexpr std::size_t kOnsetRestSamples = 3;

struct ContactClock {
    // The first valid sample at which a channel lies settings.min_amplitude or
    // more above its resting level (the median of its first kOnsetRestSamples
    // valid readings).
    std::size_t onset = 0;
    std::size_t channel = 0;  // position in `channels` of the channel that rose (the largest rise on a tie)
    // Samples from the onset to the first valid sample at which that channel,
    // past its maximum, has fallen back to half its rise above rest; nullopt
    // until it has.
    std::optional<std::size_t> unit;
};

// The clock of `trial` on `channels` (indices into trial.channels), reading
// samples [0, settings.prefix) when a prefix is set; nullopt before the onset
// (or when the recording has too few valid samples to know a resting level).
// Causal: appending samples never moves the onset or a unit already found.
std::optional<ContactClock> contact_clock(const TrialData& trial, std::span<const std::size_t> channels,
                                          const SeriesSettings& settings);

}  // namespace rollsense::series
