// The files a dataset folder owns (docs/dataset-format.md): what a run
// recorded and what identifies it. Nothing but the dataset's own writers may
// replace them: rs.write_output refuses these names, and the -o of features,
// evaluate, train and report refuses a path that is one of them, so that a
// slip of the command line never destroys the data it reads.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "rollsense/status.hpp"

namespace rollsense {

// True for a name at the top of a dataset folder that belongs to the dataset:
// manifest.csv, dataset-info.csv, run-info.csv (and the earlier runs'
// run-info.N.csv), run-config.csv, shard-plan.csv, shards.csv and the folder trials.
bool is_dataset_file(std::string_view name);

// A resumed dataset keeps the run-info.csv of each earlier run of it as
// run-info.N.csv, N = 1 for the first run (docs/dataset-format.md).
std::string earlier_run_info_name(std::size_t n);
// N of a run-info.N.csv name (N >= 1, plain digits); 0 for any other name.
std::size_t earlier_run_number(std::string_view name);

// Whether `dir` holds a dataset: its manifest.csv or its dataset-info.csv.
bool holds_dataset(const std::filesystem::path& dir);

// Refuses to begin a new dataset in `dir` when it already holds one: the way
// on is --resume or another folder.
Status check_no_dataset_in(const std::filesystem::path& dir);

// Refuses `target` (a file about to be written) when it is one of the files of
// the dataset in `dataset_dir` or lies under its trials/ (after resolving '.',
// '..' and symbolic links). The error names the target, the dataset and the way
// out; `what` names where the path came from (e.g. "-o").
Status check_not_dataset_file(const std::filesystem::path& target, const std::filesystem::path& dataset_dir,
                              std::string_view what);

}  // namespace rollsense
