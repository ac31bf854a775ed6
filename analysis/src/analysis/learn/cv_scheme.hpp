// Cross-validation schemes that show what an accuracy owes to the recording
// protocol, beside random (stratified) k-fold: grouped folds on any manifest
// column (speed: leave-one-speed-out) and blocked folds (runs of N consecutive
// trials within a mount), so correlated neighbours never straddle training and
// test. docs/identification.md "Grouped and blocked cross-validation".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/features.hpp"
#include "analysis/learn/folds.hpp"

namespace rollsense::learn {

struct CvScheme {
    enum class Kind { grouped, blocked };
    Kind kind = Kind::grouped;
    std::string group_by;  // grouped: the manifest column
    int block = 0;         // blocked: trials per block
    // "grouped by speed", "blocked by 10 trials within a mount": for reports.
    std::string describe() const;
    // "grouped:speed", "blocked:10": for evaluation.json.
    std::string id() const;
};

// --cv LIST (random, grouped, blocked; comma-separated) with --group-by and
// --block: the schemes to run beside random k-fold (random itself always runs),
// in the order the list names them (each once), which every output keeps.
// A scheme without its option, an option without its scheme, or an unknown
// word is an error naming the way out.
Result<std::vector<CvScheme>> parse_cv_schemes(const std::string& list, const std::string& group_by,
                                               const std::string& block);

// The value of manifest column `column` for a row: trial_id, object, speed,
// repetition, mount, index_in_mount (in datasets that record them; the reader
// keeps them with the trial's metadata), or a key of the manifest's `extra`
// column. nullopt: the row has no such column.
std::optional<std::string> manifest_value(const features::FeatureRow& row, const std::string& column);

// The group of every used row (rows[row_of[i]]). Blocked: mount (the `mount`
// column, or the object where the manifest has none) and the block
// index_in_mount / N, where index_in_mount is the column, or else the trial's
// position among its mount's rows in manifest order (every row counts,
// rejected ones included, so a block is N consecutive rolls).
Result<std::vector<std::string>> scheme_groups(const CvScheme& scheme, const std::vector<features::FeatureRow>& rows,
                                               const std::vector<std::size_t>& row_of);

// The fold plan of a scheme. Grouped with no more groups than k: leave one
// group out (one fold per group, one repetition: it is deterministic).
// Otherwise `repeats` grouped k-fold partitions. Refused when some fold's
// test classes never occur in its training folds: the grouping is the class
// (one mount per object), and no classifier can name a class it never saw.
Result<FoldPlan> make_scheme_plan(const CvScheme& scheme, const std::vector<int>& labels,
                                  const std::vector<std::string>& class_names,
                                  const std::vector<std::string>& groups, int k, int repeats, std::uint64_t seed);

}  // namespace rollsense::learn
