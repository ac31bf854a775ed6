// What `rollsense run` adds around a run's dataset: the run configuration
// that --resume compares (rollsense/run_config.hpp), the exact command that
// resumes an interrupted run, and the removal of an output folder that a
// run created and failed before filling.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rollsense/run_config.hpp"

namespace rollsense::cli {

// The --set options as given, KEY and VALUE split at the first '=' (a key
// given twice keeps its last value, as the settings do).
using SetOptions = std::vector<std::pair<std::string, std::string>>;

// Script (file name and FNV-1a of its bytes), profile (as named and FNV-1a of
// its file), seed, every --set and the software version. Not --out, --resume
// or options that change how, not what, is recorded (limits, progress, logging).
RunConfig run_config_of(const std::filesystem::path& script, const std::string& profile,
                        const std::filesystem::path& profile_file, std::uint64_t seed, const SetOptions& sets);

// `text` as one shell word: unchanged when it is plain, else in single quotes.
std::string shell_quote(const std::string& text);

// "rollsense run SCRIPT --out DIR --resume [--profile P] [--seed N] [--set K=V ...]",
// each word quoted for the shell. `options` are the options that decide the
// trials, as given ({"--profile", "etroll"}, {"--set", "runs=2"}, ...).
std::string resume_command(const std::string& script, const std::filesystem::path& out,
                           const std::vector<std::pair<std::string, std::string>>& options);

// Removes `dir` when it holds nothing but an empty dataset (its own files,
// no trial); true if removed. For a run that created the folder and failed
// before its first trial: the failure leaves nothing behind.
bool remove_empty_dataset(const std::filesystem::path& dir);

}  // namespace rollsense::cli
