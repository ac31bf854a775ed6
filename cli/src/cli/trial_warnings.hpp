// What the learning commands (features, evaluate, train, report) say about
// trials they could not read: the row of such a trial is rejected with the
// reason "unreadable (file:line: ...)" (features.csv, evaluation.json), and
// the terminal gets one warning per file, so a damaged trial is never left out
// unnoticed.
#pragma once

#include <vector>

#include "rollsense/features.hpp"
#include "rollsense/status.hpp"

namespace rollsense::cli {

// Logs one warning per unreadable trial: its id, file:line and the reason; an error instead when no trial could be
// read (then the fault is likely the dataset's, not each file's).
Status warn_unreadable_trials(const std::vector<features::FeatureRow>& rows);

}  // namespace rollsense::cli
