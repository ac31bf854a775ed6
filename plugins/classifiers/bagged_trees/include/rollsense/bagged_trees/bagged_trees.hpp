// The `bagged_trees` classifier plugin: MATLAB Classification Learner's
// "Bagged Trees" preset (30 learners, Gini, grown-out trees, bootstrap,
// posterior averaging) behind rollsense's Classifier interface.
#pragma once

#include "rollsense/bagged_trees/ensemble.hpp"
#include "rollsense/classifier.hpp"

namespace rollsense::bagged_trees {

// Parameters: learners, min_leaf_size, max_num_splits, predictors_per_split,
// split_criterion, seed, threads (see the schema's docs).
ParamSchema bagged_trees_schema();
// A ParamSet (validated or hand-made; missing keys take the defaults) as options.
Result<EnsembleOptions> options_from(const ParamSet& params);

class BaggedTrees final : public Classifier {
public:
    BaggedTrees() = default;
    explicit BaggedTrees(const EnsembleOptions& options) : options_(options) {}

    Status on_configure(const ParamSet& params, const PluginContext& context) override;

    // classifier.md §3 (what the paper's optimiser searched): learners 10…500
    // (log), min_leaf_size 1…max(2, floor(n/2)) (log), max_num_splits
    // 1…max(2, n−1) (log), predictors_per_split 1…max(2, p), split_criterion
    // gdi / twoing / deviance.
    SearchSpace search_space(std::size_t rows, std::size_t cols) const override;

    Status train(const FeatureTable& data) override;
    Result<Prediction> predict(std::span<const double> features) const override;
    std::vector<std::string> class_names() const override { return model_.class_names(); }
    Status save(const std::filesystem::path& file) const override { return model_.save(file); }
    Status load(const std::filesystem::path& file) override;

    // "info" → number of trees, nodes, classes, options (for `rollsense` listings).
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    const EnsembleOptions& options() const { return options_; }
    const Ensemble& model() const { return model_; }

private:
    EnsembleOptions options_;
    Ensemble model_;
};

}  // namespace rollsense::bagged_trees
