// The output files of features, evaluate, train and report, checked before any work: each can be written
// (rollsense/atomic_file.hpp: not a folder, its folder exists and is writable), none is a file of the dataset the
// command reads (rollsense/dataset_files.hpp), nor an existing result of another command (a run's model.rsm given
// to evaluate -o). An hour of evaluation is not lost to a mistyped -o, and a slip never overwrites the data.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rollsense::cli {

class Args;

// 0 when every file of `outputs` may be written; else prints the first problem once ("rollsense COMMAND: ...") and
// returns the exit code: 2 for a file of the dataset `input` (when `input` is a dataset folder) or another command's
// result, 5 for a path that cannot be written.
int check_output_files(const char* command, const std::filesystem::path& input,
                       const std::vector<std::filesystem::path>& outputs);

// -o / --output as given, with the usual `-` for standard output (/dev/stdout: rollsense/atomic_file.hpp writes it in
// place; a command that writes several files refuses it).
std::string output_option(const Args& args);

}  // namespace rollsense::cli
