// The identification feature pipeline (method.md §4), shared by every
// classifier, the CLI and the report:
//
//   raw channels ──smooth──▶ peak per channel ──valid?──▶ clean / rejected(reason)
//                                              └──────────▶ 13 features F1…F13
//
// F1–F3   amplitude of ch1..ch3
// F4–F6   skewness of ch1..ch3: (peak mid-point − time of max) / width
// F7–F9   half-width of ch1..ch3 / width of ch2
// F10–F11 width of ch1 and ch3 / width of ch2
// F12–F13 (t_max ch2 − t_max ch1) / width ch2, (t_max ch3 − t_max ch2) / width ch2
//
// Only ratios of times survive so that neither the rolling speed nor the
// object's size leaks in through the traversal time.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "rollsense/classifier.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/features/peak.hpp"
#include "rollsense/features/settings.hpp"
#include "rollsense/features/smoothing.hpp"
#include "rollsense/status.hpp"

namespace rollsense::features {

inline constexpr std::size_t kChannels = 3;
inline constexpr std::size_t kFeatureCount = 13;

// "F1" … "F13".
const std::array<std::string, kFeatureCount>& feature_names();
// One line per feature, e.g. "amplitude of channel 1".
const std::array<std::string, kFeatureCount>& feature_descriptions();

// Why a channel's peak is not valid. The first reason found per channel is kept.
enum class Rejection {
    none,
    too_short,         // fewer than 3 samples: no peak can close on both sides
    not_finite,        // a NaN or infinite reading (a failed sample)
    low_amplitude,     // max ≤ min_amplitude: the object never pressed on this barometer
    incomplete_start,  // still ≥ 5 % of max at the first sample: the roll started on the sensor
    incomplete_end,    // still ≥ 5 % of max at the last sample: the object did not leave the sensor
    zero_width,        // a one-sample peak: no width to divide by
};
std::string_view to_string(Rejection r) noexcept;  // "low_amplitude", ...

struct ChannelPeak {
    Peak peak;
    int window = 1;            // smoothing window used
    double amplitude = 0.0;
    double t_start = 0.0;      // time (settings.time_base) of the peak's first and last reading
    double t_end = 0.0;
    double t_max = 0.0;
    double width = 0.0;        // t_end − t_start
    double skewness = 0.0;
    double half_width = 0.0;
    Rejection rejection = Rejection::none;
};

struct TrialFeatures {
    bool clean = false;
    // Empty when clean; otherwise one clause per failing channel, e.g.
    // "ch3 incomplete_end (still 31% of max at the last sample)".
    std::string reason;
    std::array<ChannelPeak, kChannels> channels{};
    std::array<double, kFeatureCount> values{};  // NaN when not clean
};

// Reusable extractor: keeps its scratch buffers, so extracting many trials
// allocates nothing after the first. Not thread-safe; use one per thread.
class FeatureExtractor {
public:
    explicit FeatureExtractor(FeatureSettings settings = {});
    const FeatureSettings& settings() const { return settings_; }

    // `channels` must hold exactly 3 equally long series. `time` is needed only
    // with TimeBase::timestamps (same length); otherwise it may be empty.
    // Structural problems (channel count, lengths) are errors; an invalid peak is
    // not — it gives a rejected TrialFeatures with its reason.
    Result<TrialFeatures> extract(std::span<const std::span<const double>> channels,
                                  std::span<const double> time = {});
    Result<TrialFeatures> extract(const std::vector<std::vector<double>>& channels,
                                  std::span<const double> time = {});

    // The smoothed channels of the last extract() call (for plots and checks).
    const std::array<std::vector<double>, kChannels>& smoothed() const { return smoothed_; }

private:
    FeatureSettings settings_;
    std::array<std::vector<double>, kChannels> smoothed_;
};

// ---------------------------------------------------------------- datasets --

// The three sensor channels the identification reads (features and series
// alike), as indices into the dataset's channel columns, ch1..ch3 in order:
// the columns dataset-info.csv names as `identification_channels` (the robot
// profile's key of that name), else the dataset's channels when it has
// exactly three (one sensor). More channels and no name is an error listing
// them and saying how to name three: never a silent choice. `dataset` names
// the dataset's folder in messages; empty for a recording still in memory.
Result<std::array<std::size_t, kChannels>> identification_channels(const DatasetInfo& info,
                                                                   const std::string& dataset);

// The part of a recorded trial the identification reads: the three
// identification channels and the time column, from the trial's first to its
// last valid sample. Invalid samples before and after them (a replay's reads
// past the recording's end) are not part of the roll and are left out; an
// invalid sample between valid ones stays, as the recording had it.
struct IdentificationInput {
    std::array<std::span<const double>, kChannels> channels;
    std::span<const double> time;
    std::size_t first = 0;  // index in the trial of the first sample used
};
IdentificationInput identification_input(const TrialData& data, const std::array<std::size_t, kChannels>& columns);

// One row of a features file.
struct FeatureRow {
    std::string trial_id;
    std::string object;  // the class label
    std::string speed;
    int repetition = 0;
    bool clean = false;
    std::string reason;
    std::array<double, kFeatureCount> values{};
    // Smoothing windows used (diagnostics); none for a trial that could not be
    // read, so its window_ch columns are empty like its features, not 0.
    std::array<std::optional<int>, kChannels> windows{};
    std::map<std::string, std::string> extra;  // the trial's `extra` metadata (manifest.csv)
};

// Extract every trial of a dataset, in manifest order, on `threads` threads
// (0 = hardware concurrency). Results do not depend on the thread count. The
// channels are identification_channels(); a dataset where they cannot be
// chosen is an error. A trial file that cannot be read does not stop the
// others: its row is rejected with the reason "unreadable (file:line: ...)".
// An invalid peak is a rejected row. `stop`, when given and set (Ctrl-C),
// ends the extraction with ErrorCode::cancelled.
// `known`: extraction results already taken for some trials, by trial id
// (features/recorded.hpp): those trials are not read from their files; their
// identity (object, speed, ..., extra) still comes from the manifest.
using KnownRows = std::unordered_map<std::string, FeatureRow>;
Result<std::vector<FeatureRow>> extract_dataset(const DatasetReader& dataset, const FeatureSettings& settings,
                                                unsigned threads = 0, const std::atomic<bool>* stop = nullptr,
                                                const KnownRows* known = nullptr);

// Features CSV, loadable by MATLAB's readtable / Classification Learner and by
// pandas.read_csv without options:
//   trial_id,object,speed,repetition,clean,reason,F1,…,F13,window_ch1,window_ch2,window_ch3[,extra_<key>...]
// `clean` is 1 or 0; a rejected trial's features are empty fields (NaN on load),
// and so are the windows of a trial that could not be read.
// When any trial carries `extra` metadata, one column per key follows,
// `extra_<key>`, keys sorted, empty where a trial lacks the key.
std::string format_features_csv(const std::vector<FeatureRow>& rows);
Status write_features_csv(const std::filesystem::path& file, const std::vector<FeatureRow>& rows);
// Reads a features file (the window columns are optional). Errors name the
// file, line and column.
Result<std::vector<FeatureRow>> read_features_csv(const std::filesystem::path& file);

// Clean rows as a classifier's table; classes sorted by name (C1 < C2 < … < S2,
// the order MATLAB's categorical uses). `row_index`, if given, receives for each
// table row its index in `rows`.
FeatureTable to_feature_table(const std::vector<FeatureRow>& rows, std::vector<std::size_t>* row_index = nullptr);

}  // namespace rollsense::features
