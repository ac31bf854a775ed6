// The bagged ensemble: B trees, each grown on a bootstrap sample, whose class
// posteriors are averaged (fitcensemble(..., 'Method', 'Bag')).
//
// Speed comes from the layout classifier.md §5 describes: features are sorted
// (and ranked) once per training set; a bootstrap sample is a vector of integer
// weights; each node's best split is one sweep over presorted entries with
// running class counts; the entry arrays are partitioned stably instead of
// re-sorted (tree_builder.hpp, split_search.cpp). Each tree has its own seeded
// generator (rollsense/random.hpp), so the model is identical for any thread
// count.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "rollsense/bagged_trees/tree.hpp"
#include "rollsense/classifier.hpp"
#include "rollsense/status.hpp"

namespace rollsense::bagged_trees {

struct EnsembleOptions {
    int learners = 30;        // MATLAB NumLearningCycles
    TreeOptions tree;
    std::uint64_t seed = 1;
    unsigned threads = 0;     // 0 = hardware concurrency; never changes the model
};

class Ensemble {
public:
    // Trains on a table: rows must be finite, labels in [0, classes).
    Status train(const FeatureTable& data, const EnsembleOptions& options);

    bool trained() const { return !trees_.empty(); }
    std::size_t classes() const { return class_names_.size(); }
    std::size_t predictors() const { return feature_names_.size(); }
    const std::vector<std::string>& class_names() const { return class_names_; }
    const std::vector<std::string>& feature_names() const { return feature_names_; }
    const std::vector<Tree>& trees() const { return trees_; }
    const EnsembleOptions& options() const { return options_; }

    // Averaged posterior into `scores` (classes() entries); returns the argmax
    // (the first class on a tie, as MATLAB).
    int predict(std::span<const double> x, std::span<double> scores) const;
    // Labels for every row of a row-major matrix (rows × predictors()).
    std::vector<int> predict_rows(std::span<const double> x, std::size_t rows) const;

    // Versioned text model file; see model_file.cpp for the format.
    Status save(const std::filesystem::path& file) const;
    Status load(const std::filesystem::path& file);
    std::string serialize() const;
    Status deserialize(std::string_view text, const std::string& source);

private:
    std::vector<std::string> class_names_;
    std::vector<std::string> feature_names_;
    std::vector<Tree> trees_;
    EnsembleOptions options_;
};

}  // namespace rollsense::bagged_trees
