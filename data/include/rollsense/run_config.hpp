// The run configuration of a dataset (<dir>/run-config.csv): what decides the
// trials a run records (script and its digest, profile and its digest, every
// --set, the seed, the software version), so that --resume cannot mix two
// experiments in one dataset. What legitimately differs between a part of a
// run and the whole (--out, --resume, a shard of the trials, progress and
// logging options, time and memory limits) is not part of it.
//
//   key,value
//   rollsense_version,0.1.0
//   script,paper_experiment.lua
//   script_fnv1a,9c0e...
//   profile,sim
//   profile_fnv1a,41a7...
//   seed,11
//   set.runs,2                       one row per --set, sorted by key
//
// docs/dataset-format.md documents the file.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense {

using RunConfig = std::vector<std::pair<std::string, std::string>>;

inline constexpr const char* kRunConfigFile = "run-config.csv";
// <dir>/run-info.csv, how a run went (command line, status, times, its shard): a whole run writes it as it ends, a
// shard's run as it starts. docs/dataset-format.md documents it.
inline constexpr const char* kRunInfoFile = "run-info.csv";

// Whether the run that recorded `dir` was killed before its end (or its machine stopped): its run-config.csv,
// written as a run starts, without the run-info.csv a whole run writes as it ends. A shard killed in its first
// instant, before writing its run-info.csv, looks the same.
bool run_killed_before_end(const std::filesystem::path& dir);

std::string format_run_config(const RunConfig& config);
// A row naming a file the run read ("module.NAME_fnv1a", "include.NAME_fnv1a"), which a dataset recorded before
// those rows existed lacks: resume and merge compare them only where both sides list such rows.
bool is_read_file_key(std::string_view key);
bool lists_read_files(const RunConfig& config);
// Reads <dir>/run-config.csv; an empty config when the dataset has none
// (recorded before the file existed).
Result<RunConfig> read_run_config(const std::filesystem::path& dir);
// The differences between the configuration a dataset was recorded with and
// this run's, one "KEY: recorded X, this run Y" per key (empty: the same).
std::vector<std::string> run_config_differences(const RunConfig& recorded, const RunConfig& now);
// Whether a run configured as `now` may continue the dataset in `dir`: refused
// (invalid_argument), naming every difference, when the dataset's run-config.csv
// records another configuration; not compared when either side has none.
Status check_resume_config(const std::filesystem::path& dir, const RunConfig& now);

}  // namespace rollsense
