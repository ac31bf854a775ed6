// A sharded run (`rollsense run SCRIPT --shard K/N`): one of N processes that
// together record one run. A trial's index is its position, from 0, among the
// trials the script asks about with rs.has_trial(id) (the --resume idiom every
// stock script uses); shard K records the trials whose index ≡ K (mod N) and
// is told "already there" for the others. Every trial's data derives from the
// run seed and the trial's id only, so the trials are the same whichever
// shard records them.
//
// A shard writes its plan beside its dataset, <dir>/shard-plan.csv: every trial
// the script asked about, in order, and the shard that records it
//
//   trial_id,shard
//   C1-v10-r001,0
//   C1-v10-r002,1
//
// so that `rollsense merge` can put the trials of all shards back in the
// order an unsharded run records them (docs/cluster.md, docs/dataset-format.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense {

inline constexpr const char* kShardPlanFile = "shard-plan.csv";
// A merged dataset's record of the shards it was merged from (rollsense/shard_merge.hpp).
inline constexpr const char* kShardsFile = "shards.csv";
// Far more processes than any cluster gives one run.
inline constexpr std::size_t kMaxShards = 1'000'000;

struct Shard {
    std::size_t index = 0;  // K
    std::size_t count = 1;  // N

    // "K/N", as --shard and run-info.csv spell it.
    std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
    // The shard that records the trial at `trial_index`.
    std::size_t owner(std::size_t trial_index) const { return trial_index % count; }
};

// "K/N" with whole numbers 0 <= K < N and 2 <= N <= kMaxShards (one process
// is a run without --shard); the error names `what` (e.g. "--shard") and says
// what is expected.
Result<Shard> parse_shard(std::string_view text, std::string_view what);

// The trials a sharded run's script asks about, numbered in order.
class ShardPlan {
public:
    explicit ShardPlan(Shard shard) : shard_(shard) {}

    const Shard& shard() const { return shard_; }
    // Numbers `trial_id` the first time it is asked about; true when this
    // shard records it.
    bool claim(const std::string& trial_id);
    // Ok when this shard may save the trial; otherwise why not (the script
    // never asked about it, or another shard records it) and what to do.
    Status check_save(const std::string& trial_id) const;
    const std::vector<std::string>& trials() const { return order_; }
    // The content of shard-plan.csv.
    std::string csv() const;

private:
    Shard shard_;
    std::vector<std::string> order_;
    std::unordered_map<std::string, std::size_t> index_;
};

// The command that records the missing or damaged trials of the dataset in
// `dir` again, in place: "rollsense run SCRIPT --shard K/N --out DIR --resume"
// for a shard's folder (its run-info.csv names the shard), without --shard
// for a whole run's.
std::string resume_command(const std::filesystem::path& dir);

// Reads <dir>/shard-plan.csv of a run split `count` ways: the trial ids in
// order. Every error names the file and line (a repeated id, a shard column
// that is not index mod count).
Result<std::vector<std::string>> read_shard_plan(const std::filesystem::path& dir, std::size_t count);

}  // namespace rollsense
