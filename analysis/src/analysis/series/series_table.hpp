// A dataset's trials as a table of prepared series (FeatureTable with
// series_length > 0), the input of a raw-series classifier. Every trial goes
// through prepare_series() with the same settings; refused trials are listed
// with their reasons, never silently dropped.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "analysis/series/prepare.hpp"
#include "rollsense/classifier.hpp"
#include "rollsense/dataset.hpp"

namespace rollsense::series {

struct RefusedTrial {
    std::string trial_id;
    std::string object;
    std::string reason;  // PreparedSeries::reason
};

struct SeriesTable {
    FeatureTable table;                  // rows in the order of the trials passed, refused ones left out
    std::vector<std::string> trial_ids;  // per row
    std::vector<RefusedTrial> refused;   // in the order of the trials passed
};

// Prepares `trials` (records of `dataset`) on `threads` threads (0 = hardware
// concurrency); the result does not depend on the thread count. Classes are the
// objects of the kept rows, sorted by name. A channel name the dataset does
// not record, or a trial file that cannot be read, is an error naming it.
Result<SeriesTable> series_table(const DatasetReader& dataset, std::span<const TrialRecord> trials,
                                 const std::vector<std::string>& channel_names, const SeriesSettings& settings,
                                 unsigned threads = 0);

// The channel indices of `names` in the dataset's channel columns.
Result<std::vector<std::size_t>> channel_indices(const DatasetInfo& info, const std::vector<std::string>& names);

}  // namespace rollsense::series
