// The series preparation rule (docs/series-preparation.md): how one trial's
// raw channels become the fixed-length, channel-major row a raw-series
// classifier (ClassifierInput::series) is trained on and predicts from.
//
//   raw channels ─valid?─▶ gaps interpolated ─smooth─▶ contact found ─▶ baseline removed
//                  └─ refused(reason)                                  ─▶ contact resampled to L
//                                                                      ─▶ amplitude rule
//
// One function, applied identically in training, evaluation, live
// identification and replay, so that no step can differ between them.
//
// The paper's timing rule holds for the series too: time is normalised to the
// contact (a feature inside the trial), never to the roll or the clock — a
// larger cylinder crosses the array faster, so whole-recording timing would
// name its diameter without sensing its shape. `roll_relative` breaks that rule
// on purpose (for comparison only) and is never the default.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/status.hpp"

namespace rollsense::series {

enum class Amplitude {
    global_scale,  // default: baseline-removed readings × `scale`; amplitude and channel ratios survive
    z_per_channel, // each channel to mean 0, standard deviation 1 (floored by z_floor)
};

enum class TimeAxis {
    contact,        // default, the paper's rule: resample the contact (plus margins) to `length`
    roll_relative,  // OUTSIDE THE PAPER'S RULE: resample the whole recording (or prefix) to `length`
};

struct SeriesSettings {
    std::size_t length = 128;            // samples per channel after resampling
    int detect_window = 5;               // Gaussian smoothing window (samples) used only to find the contact
    double contact_fraction = 0.10;      // a channel is in contact while its smoothed rise ≥ this × its peak rise
    double noise_floor = 0.01;           // …and ≥ this (post-filter noise is about ±0.005)
    double min_amplitude = 0.03;         // a channel whose smoothed rise stays below this never touched the object
    double margin = 0.10;                // context kept on each side, as a fraction of the contact's length
    bool require_complete_contact = true;  // refuse a contact cut off by the recording (the paper's
                                           // incomplete peaks); the end is exempt when a prefix cuts it
    Amplitude amplitude = Amplitude::global_scale;
    double scale = 1.0;                  // global_scale: one constant for every trial and channel
    double z_floor = 0.01;               // z_per_channel: never divide by less (a flat channel stays flat)
    double max_invalid_fraction = 0.10;  // refuse a trial with more invalid samples than this
    std::size_t max_gap = 5;             // refuse a trial with a run of more invalid samples than this
    std::size_t prefix = 0;              // > 0: use only samples [0, prefix) (identification before the roll ends)
    bool open_end = false;               // the roll is still going (live, before it ends): the recording's
                                         // end is a cut like a prefix's, so a contact it cuts is not refused
    TimeAxis time_axis = TimeAxis::contact;
};

// Checks the settings; the error names the setting and its allowed range.
Status validate(const SeriesSettings& settings);

std::string_view to_string(Amplitude a) noexcept;
std::string_view to_string(TimeAxis t) noexcept;

// Why a trial cannot be prepared. A refusal is an outcome, not an error:
// the trial stays in the dataset and is reported with its reason.
enum class Refusal {
    none,
    too_short,           // fewer samples (after the prefix) than the rule can work with
    too_many_invalid,    // more invalid samples than max_invalid_fraction, or none valid
    invalid_gap,         // a run of invalid samples longer than max_gap
    no_contact,          // no channel rose by min_amplitude (or not yet, within the prefix)
    incomplete_contact,  // the contact touches the recording's start (or end) edge
};
std::string_view to_string(Refusal r) noexcept;

struct PreparedSeries {
    bool ok = false;
    Refusal refusal = Refusal::none;
    std::string reason;          // empty when ok; e.g. "no_contact (largest rise 0.012 on ch2 < 0.03)"
    std::vector<double> values;  // channels × length, channel-major; empty when refused
    // Where the resampled window lies, in fractional sample indices of the
    // recording (diagnostics, plots): contact bounds and the window with margins.
    double contact_start = 0.0, contact_end = 0.0;
    double window_start = 0.0, window_end = 0.0;
    std::vector<double> baseline;  // per channel, removed before the amplitude rule
    std::size_t invalid_samples = 0;
};

// Prepares `trial`'s channels `channels` (indices into trial.channels, in the
// order the row holds them). Structural problems (no channel chosen, an index
// out of range, channel and time lengths differing, bad settings) are errors;
// a trial the rule cannot use is a refused PreparedSeries with its reason.
Result<PreparedSeries> prepare_series(const TrialData& trial, std::span<const std::size_t> channels,
                                      const SeriesSettings& settings);

}  // namespace rollsense::series
