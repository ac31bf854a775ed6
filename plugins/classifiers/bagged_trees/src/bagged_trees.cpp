#include "rollsense/bagged_trees/bagged_trees.hpp"

#include <algorithm>
#include <cmath>

namespace rollsense::bagged_trees {

ParamSchema bagged_trees_schema() {
    const EnsembleOptions d;
    return {
        param_int("learners", d.learners, "number of trees (MATLAB NumLearningCycles)", 1, 100000),
        param_int("min_leaf_size", d.tree.min_leaf_size, "minimum observations per leaf (MATLAB MinLeafSize)", 1),
        param_int("min_parent_size", d.tree.min_parent_size, "a node with fewer observations is not split", 2),
        param_int("max_num_splits", d.tree.max_num_splits,
                  "maximum splits per tree (MATLAB MaxNumSplits); 0 = n - 1, trees grown out", 0),
        param_int("predictors_per_split", d.tree.predictors_per_split,
                  "predictors tried per split: 0 = all (newer MATLAB), -1 = ceil(sqrt(p)) (older MATLAB), k = k at "
                  "random",
                  -1),
        param_string("split_criterion", std::string(to_string(d.tree.criterion)),
                     "gdi (Gini's diversity index), deviance (cross-entropy) or twoing",
                     {"gdi", "deviance", "twoing"}),
        param_int("seed", static_cast<std::int64_t>(d.seed), "seed of the bootstrap samples and predictor draws", 0),
        param_int("threads", static_cast<std::int64_t>(d.threads),
                  "training threads, 0 = all cores (the model does not depend on it)", 0, 1024),
    };
}

Result<EnsembleOptions> options_from(const ParamSet& p) {
    try {
        EnsembleOptions o;
        if (p.has("learners")) o.learners = static_cast<int>(p.get_int("learners"));
        if (p.has("min_leaf_size")) o.tree.min_leaf_size = static_cast<int>(p.get_int("min_leaf_size"));
        if (p.has("min_parent_size")) o.tree.min_parent_size = static_cast<int>(p.get_int("min_parent_size"));
        if (p.has("max_num_splits")) o.tree.max_num_splits = static_cast<int>(p.get_int("max_num_splits"));
        if (p.has("predictors_per_split"))
            o.tree.predictors_per_split = static_cast<int>(p.get_int("predictors_per_split"));
        if (p.has("split_criterion")) {
            auto c = parse_split_criterion(p.get_string("split_criterion"));
            if (!c) return c.error();
            o.tree.criterion = *c;
        }
        if (p.has("seed")) o.seed = static_cast<std::uint64_t>(p.get_int("seed"));
        if (p.has("threads")) o.threads = static_cast<unsigned>(p.get_int("threads"));
        if (o.learners < 1) return Error{ErrorCode::invalid_argument, "learners must be at least 1"};
        if (o.tree.min_leaf_size < 1) return Error{ErrorCode::invalid_argument, "min_leaf_size must be at least 1"};
        if (o.tree.predictors_per_split < -1)
            return Error{ErrorCode::invalid_argument, "predictors_per_split must be -1, 0 or a positive count"};
        return o;
    } catch (const StatusError& e) {
        return e.status();
    }
}

Status BaggedTrees::on_configure(const ParamSet& params, const PluginContext&) {
    auto o = options_from(params);
    if (!o) return o.status();
    options_ = *o;
    return {};
}

SearchSpace BaggedTrees::search_space(std::size_t rows, std::size_t cols) const {
    using Scale = SearchDimension::Scale;
    const double n = static_cast<double>(rows), p = static_cast<double>(cols);
    return {
        {"learners", Scale::integer_log, 10, 500, {}},
        {"min_leaf_size", Scale::integer_log, 1, std::max(2.0, std::floor(n / 2)), {}},
        {"max_num_splits", Scale::integer_log, 1, std::max(2.0, n - 1), {}},
        {"predictors_per_split", Scale::integer_linear, 1, std::max(2.0, p), {}},
        {"split_criterion", Scale::categorical, 0, 0, {"gdi", "twoing", "deviance"}},
    };
}

Status BaggedTrees::train(const FeatureTable& data) { return model_.train(data, options_); }

Result<Prediction> BaggedTrees::predict(std::span<const double> features) const {
    if (!model_.trained())
        return Error{ErrorCode::state_error, "bagged_trees: predict before train or load"};
    if (features.size() != model_.predictors())
        return Error{ErrorCode::invalid_argument, "bagged_trees: got " + std::to_string(features.size()) +
                                                      " features, the model was trained on " +
                                                      std::to_string(model_.predictors())};
    for (std::size_t i = 0; i < features.size(); ++i)
        if (!std::isfinite(features[i]))
            return Error{ErrorCode::invalid_argument,
                         "bagged_trees: feature '" + model_.feature_names()[i] + "' is not a finite number"};
    Prediction p;
    p.scores.resize(model_.classes());
    p.label = model_.predict(features, p.scores);
    p.class_name = model_.class_names()[static_cast<std::size_t>(p.label)];
    return p;
}

Status BaggedTrees::load(const std::filesystem::path& file) {
    Ensemble loaded;
    if (auto s = loaded.load(file); !s) return s;
    model_ = std::move(loaded);
    const unsigned threads = options_.threads;
    options_ = model_.options();
    options_.threads = threads;
    return {};
}

Result<ValueMap> BaggedTrees::invoke(const std::string& verb, const ValueMap& args) {
    if (verb != "info") return Classifier::invoke(verb, args);
    ValueMap out;
    std::int64_t nodes = 0;
    for (const auto& t : model_.trees()) nodes += static_cast<std::int64_t>(t.nodes());
    out["trained"] = model_.trained();
    out["trees"] = static_cast<std::int64_t>(model_.trees().size());
    out["nodes"] = nodes;
    out["classes"] = model_.class_names();
    out["features"] = model_.feature_names();
    out["learners"] = std::int64_t{options_.learners};
    out["split_criterion"] = std::string(to_string(options_.tree.criterion));
    return out;
}

}  // namespace rollsense::bagged_trees
