// `rollsense merge OUT SHARD...`: the datasets of the N shards of one run
// (rollsense/shard.hpp) joined into the dataset the unsharded run records:
// trials/, manifest.csv (the trials in the run's order), dataset-info.csv and,
// when the shards have one, run-config.csv are byte-identical to it.
//
// Refused, with nothing written, unless the shards are exactly one run's:
// shards 0..N-1 of one N, each finished (run-info.csv status ok), recorded with
// one configuration (dataset-info.csv and run-config.csv, or without that file
// the script, profile, seed and --set options of run-info.csv), with one plan
// (shard-plan.csv), and between them every planned trial once. Each error
// names the shard folder and the difference.
//
// The merged folder also gets shards.csv (one row per shard: where it came
// from, its trials, when and how it ran; docs/dataset-format.md); run-info.csv
// and features.csv are the caller's (`finish`).
//
// Everything is written into a hidden sibling folder (.OUT.tmp-PID) that is
// renamed to OUT at the end, so a refusal or a failure (a damaged trial, a full
// disk, an error of `finish`) leaves OUT as it was, and a retry is not refused.
// Errors name the files under OUT, not under the sibling; a sibling that cannot
// be created (OUT's folder not writable) names that folder, the reason and the way out.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense {

struct MergeSummary {
    std::size_t shards = 0;
    std::size_t trials = 0;
    std::string command_line;  // that recorded shard 0 (its run-info.csv), words quoted for the shell
    std::string working_dir;   // where it ran (empty for a shard recorded before run-info.csv had it)
};

// Called with the merged folder before it becomes `out` (it is still the
// sibling): the caller's own files go there.
using MergeFinish = std::function<Status(const std::filesystem::path& merged, const MergeSummary& summary)>;

// What the command line alone decides, checked before any shard is read: `out`
// (its links followed) new or an empty folder, not a file, and each shard
// folder given once however it is spelt (./A, A/, a link to A). Its refusals
// are invalid_argument, which `rollsense merge` reports as a usage error (exit
// 2, as `run --out` into a folder that is not empty); merge_shards checks the same.
Status check_merge_arguments(const std::filesystem::path& out, const std::vector<std::filesystem::path>& shards);

// `out` must not exist or be an empty folder (which keeps its permissions); a
// symbolic link is followed (its folder takes the merge, the link stays). The
// shards are locked while they are read (a shard still being recorded is refused).
Result<MergeSummary> merge_shards(const std::filesystem::path& out, const std::vector<std::filesystem::path>& shards,
                                  const MergeFinish& finish = {});

}  // namespace rollsense
