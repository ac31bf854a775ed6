// A saved model file's header, read without a plugin: its first word names the classifier plugin that wrote it
// ("rollsense-bagged-trees 1"), and a series model records its input ("channel NAME", "series_length N" lines).
// `rollsense predict MODEL` and rs.classifier{model=} find the plugin by it (the latter only where it names one).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::learn {

struct ModelHeader {
    std::string magic;                  // the first line's first word
    std::vector<std::string> channels;  // "channel NAME" lines
    std::size_t series_length = 0;      // "series_length N"
};

// Whether `model` can be a model file, or an error naming it and the way out: missing, a folder, not a regular file (a
// pipe or a device such as /dev/stdin, which would hang or never end: sandbox review), empty.
Status check_model_file(const std::filesystem::path& model);

// The header of `model` (checked as above; at most its first MiB is read), or an error naming the file and the way out.
Result<ModelHeader> read_model_header(const std::filesystem::path& model);

// "rollsense-bagged-trees" → "bagged_trees": the plugin a model file names, or an error saying it names none, in
// `rollsense predict`'s words.
Result<std::string> plugin_named_by(const ModelHeader& header, const std::filesystem::path& model);

// Said after an error about the plugin a model file named: where the name came from, and `way_out` (how to name
// another: "give --classifier NAME").
std::string named_by_note(const std::filesystem::path& model, const std::string& way_out);

}  // namespace rollsense::learn
