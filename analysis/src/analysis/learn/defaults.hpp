// Defaults of the analysis commands, kept in one data file,
// share/analysis/defaults.csv ("key,value" rows), so that no C++ outside a
// classifier's plugin names that classifier.
#pragma once

#include <filesystem>
#include <string>

#include "rollsense/status.hpp"

namespace rollsense::learn {

// <share_dir>/analysis/defaults.csv
std::filesystem::path defaults_file(const std::filesystem::path& share_dir);

// The value of `key`; errors name the file (and line) and what to fix.
Result<std::string> analysis_default(const std::filesystem::path& share_dir, const std::string& key);

// The classifier plugin used when none is named (key "classifier").
Result<std::string> default_classifier(const std::filesystem::path& share_dir);

// `given` when not empty, else default_classifier(share_dir).
Result<std::string> classifier_or_default(const std::string& given, const std::filesystem::path& share_dir);

// `text` with every "{default_classifier}" replaced by the default read from
// share_dir, or by "none: <why>" when it cannot be read (for --help texts,
// which must print whatever is true of this installation).
std::string with_default_classifier(std::string text, const std::filesystem::path& share_dir);

}  // namespace rollsense::learn
