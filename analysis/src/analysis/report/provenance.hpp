// Where a dataset and its report came from: the recording's run-info.csv
// (date, command line, software version, profile, script, seed), the
// deterministic dataset-info, and how this report was made.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rollsense/csv.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/status.hpp"

namespace rollsense::report {

using KeyValues = csv::KeyValues;

// run-info.csv as written by the recorder; a dataset without one (made by
// hand) gives an empty list. A malformed file is an error naming its line.
Result<KeyValues> read_run_info(const std::filesystem::path& dataset_dir);

std::string utc_timestamp();  // "2026-11-21T02:11:30Z"

}  // namespace rollsense::report
