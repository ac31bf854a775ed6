// Inputs of the learning commands: a dataset folder or a features CSV, and
// "key=value" classifier parameters from the command line or Lua.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rollsense/features.hpp"
#include "rollsense/features/recorded.hpp"
#include "analysis/learn/evaluate.hpp"

namespace rollsense::learn {

// A folder is a recorded dataset (features extracted with `settings`); a file
// is a features CSV written by `rollsense features` (or by hand).
// `stop`: as in features::extract_dataset.
// `recorded`: features this run took from memory (features/recorded.hpp, with
// `settings`); only the dataset's other trials are read from their files.
Result<std::vector<features::FeatureRow>> load_feature_rows(const std::filesystem::path& input,
                                                            const features::FeatureSettings& settings,
                                                            unsigned threads = 0,
                                                            const std::atomic<bool>* stop = nullptr,
                                                            const features::RecordedFeatures* recorded = nullptr);

// "learners=100" → integer, "rate=0.1" → number, "x=true" → boolean,
// anything else a string. Errors name the text.
Status parse_assignment(const std::string& text, ParamSet& into);

// What the learning commands (rollsense evaluate / train) were asked to do.
struct CommandSetup {
    std::string input;                 // dataset folder or features CSV
    EvaluationOptions options;
    std::string classifier;            // plugin name; the CLI fills in default_classifier() (defaults.hpp)
    std::vector<std::filesystem::path> plugin_path;
};

// "clean 1164 of 1350; rejected: ch3 incomplete_end 120, ch1 low_amplitude 66"
std::string summarize_rejections(const std::vector<features::FeatureRow>& rows);

}  // namespace rollsense::learn
