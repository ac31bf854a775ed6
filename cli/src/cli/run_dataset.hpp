// What `rollsense run` adds around a run's dataset: the run configuration
// that --resume compares (rollsense/run_config.hpp), the exact command that
// resumes an interrupted run (or analyses a recording whose analysis failed),
// the trials a dataset holds, and the removal of an output folder that a
// run created and failed before filling.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rollsense/run_config.hpp"
#include "rollsense/shard.hpp"
#include "rollsense/status.hpp"

namespace rollsense::cli {

// The --set options as given, KEY and VALUE split at the first '=' (a key
// given twice keeps its last value, as the settings do).
using SetOptions = std::vector<std::pair<std::string, std::string>>;

// Script (file name and FNV-1a of its bytes), profile (as named and FNV-1a of
// its file), the modules the script requires and the profiles the profile
// includes (FNV-1a each), seed, every --set and the software version. Not --out,
// --resume or options that change how, not what, is recorded (limits, progress, logging).
RunConfig run_config_of(const std::filesystem::path& script, const std::string& profile,
                        const std::filesystem::path& profile_file, const std::filesystem::path& share_dir,
                        std::uint64_t seed, const SetOptions& sets);

// "rollsense run SCRIPT --out DIR --resume [--profile P] [--seed N] [--set K=V ...]",
// each word quoted for the shell. `options` are the options that decide the
// trials, as given ({"--profile", "etroll"}, {"--set", "runs=2"}, ...).
std::string resume_command(const std::string& script, const std::filesystem::path& out,
                           const std::vector<std::pair<std::string, std::string>>& options);

// The trials the manifest of the dataset in `dir` lists (0: none, or it cannot be read).
std::size_t trials_listed(const std::filesystem::path& dir);

// The commands that redo what rs.analyse makes from `dataset` (evaluation, report,
// model), into `out`: "rollsense report DATASET; rollsense train DATASET -o OUT/model.rsm",
// each word quoted for the shell.
std::string analysis_commands(const std::filesystem::path& dataset, const std::filesystem::path& out);

// --out checked before the run starts, so a refusal writes nothing. A new or
// empty folder is fine, and so is one holding a dataset (manifest.csv or
// dataset-info.csv: the dataset writer then refuses it without --resume, or
// checks with --resume that it is this run's). Refused: a file, or a path
// through a file (check_can_be_folder); a folder holding other
// files, which the run would write over (--resume continues datasets only);
// and a --resume whose --shard is not the folder's (run-info.csv's shard K/N,
// shard-plan.csv): a shard is resumed as that shard, a whole run without one.
// The error names the folder, what it holds and the way out.
Status check_out_folder(const std::filesystem::path& dir, bool resume, const std::optional<Shard>& shard);

// The names and modification times of what `dir` holds (of `dir` itself when it
// is a file; empty when it does not exist). Taken before and after a failed
// run, it tells whether the run wrote anything there worth pointing to.
std::map<std::string, std::filesystem::file_time_type> folder_state(const std::filesystem::path& dir);

// Removes `dir` when it holds nothing but an empty dataset (its own files,
// no trial: rollsense/dataset_files.hpp); true if removed. For a run that created the folder and failed
// before its first trial: the failure leaves nothing behind.
bool remove_empty_dataset(const std::filesystem::path& dir);

}  // namespace rollsense::cli
