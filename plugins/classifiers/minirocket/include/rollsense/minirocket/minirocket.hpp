// The `minirocket` classifier plugin: the MiniRocket transform of the prepared
// multichannel series, features standardised with the training statistics, a
// ridge classifier with α chosen by closed-form leave-one-out. Scores are the
// softmax of the one-vs-rest decision values (they sum to 1 and keep their
// order; they are not calibrated probabilities).
#pragma once

#include <string>
#include <vector>

#include "rollsense/classifier.hpp"
#include "rollsense/minirocket/transform.hpp"

namespace rollsense::minirocket {

struct Options {
    TransformOptions transform;
    double log10_alpha_low = -3.0, log10_alpha_high = 3.0;
    int alphas = 10;
    unsigned threads = 0;  // 0 = all cores; the model does not depend on it
};

// Parameters: num_features, max_dilations_per_kernel, alpha_log10_low,
// alpha_log10_high, alphas, seed, threads (see the schema's docs).
ParamSchema minirocket_schema();
Result<Options> options_from(const ParamSet& params);

// The fitted model: transform, standardisation and ridge weights.
struct Model {
    std::vector<std::string> class_names, channel_names;
    std::string series_rule;               // FeatureTable::series_rule of training: stored, never read here
    Transform transform;
    std::vector<float> mean, scale;        // per feature, training statistics (scale 1 where constant)
    std::vector<float> weights;            // features × classes, row-major, on standardised features
    std::vector<double> intercept;         // classes
    double alpha = 0.0;
    std::vector<double> loo_error;         // per α of the grid (informational)

    bool trained() const { return !intercept.empty(); }
    std::size_t classes() const { return intercept.size(); }
    std::size_t row_width() const { return transform.channels() * transform.length(); }

    std::string serialize(const Options& options) const;
    // Replaces *this and the model-defining fields of options on success only.
    Status deserialize(std::string_view text, const std::string& source, Options& options);
};

class MiniRocket final : public Classifier {
public:
    MiniRocket() = default;
    explicit MiniRocket(const Options& options) : options_(options) {}

    Status on_configure(const ParamSet& params, const PluginContext& context) override;

    ClassifierInput input() const override { return ClassifierInput::series; }
    // Nothing to tune: α is already chosen by leave-one-out inside every
    // training set, and the paper's defaults (≈10,000 features, 32 dilations)
    // are insensitive on its 128 data sets; searching them would multiply the
    // cost of an evaluation for no expected gain.
    SearchSpace search_space(std::size_t, std::size_t) const override { return {}; }

    Status train(const FeatureTable& data) override;
    Result<Prediction> predict(std::span<const double> series) const override;
    // Decision values of many rows at once (rows × classes), for benches and CV.
    Result<std::vector<Prediction>> predict_many(std::span<const double> rows, std::size_t count) const;
    std::vector<std::string> class_names() const override { return model_.class_names; }
    std::string series_rule() const override { return model_.series_rule; }
    Status save(const std::filesystem::path& file) const override;
    Status load(const std::filesystem::path& file) override;

    // "info" → features, dilations, chosen α, classes, channels, series length.
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    const Options& options() const { return options_; }
    const Model& model() const { return model_; }

private:
    Status check_row_width(std::size_t width) const;
    Prediction decide(const float* features) const;

    Options options_;
    Model model_;
};

}  // namespace rollsense::minirocket
