// Classifier plugin interface: trained on a table of trials (feature vectors, or prepared series), predicts a class
// with per-class scores, saves and loads its model, and declares what it takes and what tuning may search.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "rollsense/component.hpp"

namespace rollsense {

// What a classifier takes as one trial.
enum class ClassifierInput {
    features,  // a feature vector (the paper's 13 features)
    series,    // the trial's prepared series: every channel resampled to one length
};

// Rows are trials; row-major for cheap row access. A row is either a feature vector (series_length == 0: one column
// per feature name) or a prepared series (series_length > 0: channel_names.size() × series_length samples, channel by
// channel). Folds, subsets and predictions treat both alike.
struct FeatureTable {
    std::vector<std::string> feature_names;  // feature vectors
    std::vector<std::string> channel_names;  // series
    std::size_t series_length = 0;           // samples per channel; 0 = feature vectors
    std::string series_rule;                 // how the series were prepared; opaque, saved and loaded with the model
    std::vector<std::string> class_names;    // label i is class_names[i]
    std::size_t rows = 0;
    std::vector<double> x;                   // rows * cols()
    std::vector<int> y;                      // rows labels in [0, class_names.size())

    ClassifierInput input() const { return series_length ? ClassifierInput::series : ClassifierInput::features; }
    std::size_t cols() const { return series_length ? channel_names.size() * series_length : feature_names.size(); }
    std::span<const double> row(std::size_t i) const { return {x.data() + i * cols(), cols()}; }
};

// One hyperparameter tuning may search: its name (a parameter of the plugin's
// schema), scale and inclusive range, or its choices.
struct SearchDimension {
    enum class Scale { integer_log, integer_linear, real_log, real_linear, categorical };
    std::string name;
    Scale scale = Scale::integer_linear;
    double low = 0.0, high = 1.0;      // numeric scales
    std::vector<std::string> choices;  // categorical
};
using SearchSpace = std::vector<SearchDimension>;

struct Prediction {
    int label = -1;
    std::string class_name;
    std::vector<double> scores;  // one per class, >= 0, summing to 1 (posterior estimate); the label's is the highest
};

class ROLLSENSE_API Classifier : public Component {
public:
    // The input this classifier is trained on and predicts from.
    virtual ClassifierInput input() const { return ClassifierInput::features; }
    // What tuning may search for a training set of `rows` trials of `cols`
    // columns (ranges may depend on them); empty = nothing to tune.
    virtual SearchSpace search_space(std::size_t /*rows*/, std::size_t /*cols*/) const { return {}; }
    virtual Status train(const FeatureTable& data) = 0;
    virtual Result<Prediction> predict(std::span<const double> features) const = 0;
    virtual std::vector<std::string> class_names() const = 0;
    virtual Status save(const std::filesystem::path& file) const = 0;
    virtual Status load(const std::filesystem::path& file) = 0;
    virtual std::string series_rule() const { return {}; }  // the trained (or loaded) FeatureTable::series_rule
};

}  // namespace rollsense
