// The `nearest_centroid` classifier plugin: each feature is standardised with
// the training set's mean and standard deviation (a constant feature is
// ignored), each class is represented by the mean of its trials (its
// centroid), optionally shrunk towards the overall mean (Tibshirani et al.'s
// "nearest shrunken centroid": every standardised centroid coordinate is
// moved towards 0 by `shrink`, and stops at 0), and a trial goes to the class
// whose centroid is nearest in Euclidean distance. Scores are a softmax of
// −distance / temperature: they sum to 1 and rank the classes as the
// distances do. A class without training trials has no centroid: it is never
// predicted and scores 0.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rollsense/classifier.hpp"

namespace rollsense::nearest_centroid {

struct Options {
    double shrink = 0.0;       // soft threshold on standardised centroid coordinates (0 = plain nearest centroid)
    double temperature = 1.0;  // of the score softmax, in standardised distance units
};

// The trained model, all in standardised units.
struct Model {
    std::vector<std::string> class_names;
    std::vector<std::uint64_t> class_rows;  // training trials per class (0 = no centroid)
    std::vector<std::string> feature_names;
    std::vector<double> mean, sd;           // per feature; sd == 0: feature ignored
    std::vector<double> centroids;          // class-major, class_names.size() × feature_names.size()
    Options options;

    bool trained() const { return !class_names.empty(); }
    bool used(std::size_t feature) const { return sd[feature] > 0.0; }

    std::string serialize() const;
    // Errors name `source` and the line, and say what to do.
    Status deserialize(std::string_view text, const std::string& source);
};

// Parameters: shrink, temperature (see the schema's docs).
ParamSchema nearest_centroid_schema();

class NearestCentroid final : public Classifier {
public:
    Status on_configure(const ParamSet& params, const PluginContext& context) override;

    // shrink 0…2 (linear): how far centroids are pulled together, in
    // standard deviations. The temperature is not searched: it does not
    // change which class is nearest, so it cannot change an accuracy.
    SearchSpace search_space(std::size_t rows, std::size_t cols) const override;

    Status train(const FeatureTable& data) override;
    Result<Prediction> predict(std::span<const double> features) const override;
    std::vector<std::string> class_names() const override { return model_.class_names; }
    Status save(const std::filesystem::path& file) const override;
    Status load(const std::filesystem::path& file) override;

    // "info" → classes, features used and ignored, options.
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    const Model& model() const { return model_; }

private:
    Options options_;
    Model model_;
};

}  // namespace rollsense::nearest_centroid
