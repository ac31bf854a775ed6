// The contact's onset, as a live run sees it: the first sample at which the
// object is seen pressing, found from that sample and the ones before it only.
//
// Identification before the roll ends cuts its prefixes from here, not from
// record_start: the paper's timing rule puts time zero at the contact, never
// at the roll or the clock. When the object first touches the array, relative
// to the start of the recording, depends on where it sits and how large it
// is; a prefix cut from record_start shows more of a contact that began
// earlier, and so would let a classifier read the object from the onset's
// timing rather than from its shape.
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

// The index of the first valid sample at which a channel of `channels`
// (indices into trial.channels) lies settings.min_amplitude or more above its
// resting level (the median of its first kOnsetRestSamples valid readings),
// looking at samples [0, settings.prefix) when a prefix is set; nullopt when
// no channel has risen so far (or the recording has too few valid samples
// to know a resting level). Causal: appending samples never moves it.
std::optional<std::size_t> contact_onset(const TrialData& trial, std::span<const std::size_t> channels,
                                         const SeriesSettings& settings);

}  // namespace rollsense::series
