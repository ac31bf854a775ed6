// A dataset that holds only part of its run is analysed as given, but said so.
#pragma once

#include <filesystem>

namespace rollsense::cli {

// Warns (once) when `dataset` is a folder a run is recording now, one shard of a sharded run, or the
// dataset of a run that did not end ok (run-info.csv): its trials are then only a part of the run's. Nothing for a
// file (a features table) or a complete dataset.
void warn_if_partial(const std::filesystem::path& dataset);

}  // namespace rollsense::cli
