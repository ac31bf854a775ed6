// `rollsense run SCRIPT --check`: what a run checks before its first trial, without running one: the profile with its
// overrides, each device's plugin and its parameters against the plugin's schema, and the script's declared settings
// against --set. For a batch system (tools/slurm/submit.sh), where a mistyped --set would fail every queued shard.
// No device is configured: what a plugin itself refuses then (a port that does not open, a servo that does not
// answer, a parameter its schema cannot express) is found when a run starts its devices.
#pragma once

#include <filesystem>
#include <string>

#include "runtime/session/session.hpp"

namespace rollsense::cli {

// 0 with a line saying what was checked, or a StatusError naming the refused setting (bad_setting: exit 2) or the
// script or profile that does not load. `script_arg` is the SCRIPT as given, for messages.
int check_run_settings(const runtime::SessionOptions& options, const std::string& script_arg);

}  // namespace rollsense::cli
