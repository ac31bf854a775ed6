// A classifier plugin as someone outside this repository might write it, whose
// parameter `mode` chooses what its predictions get wrong, or where it throws,
// so that tests see every command refuse them (a plugin error naming it)
// instead of writing them into evaluation.json, printing them or ending with an
// "unexpected error". mode 0 predicts honestly: the class of the nearest
// training mean of the first feature, with scores summing to 1.
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

ParamSchema odd_scores_schema() {
    return {param_int("mode", std::int64_t{0},
                      "0 honest; 1 NaN scores; 2 two scores whatever the class count; 3 label 99; 4 a wrong class "
                      "name; 5 a score of 7; 6 a negative score; 7 the highest score not the label's; 8 throws in "
                      "predict; 9 throws in train; 10 throws in load; 11 throws in input; 12 throws in search_space; 13 "
                      "throws in class_names; 14 train refuses (an error status); 15 no class names once trained",
                      0, 15)};
}

class OddScores final : public Classifier {
public:
    Status on_configure(const ParamSet& p, const PluginContext&) override {
        mode_ = p.get_int("mode");
        return {};
    }
    ClassifierInput input() const override {
        if (mode_ == 11) throw std::runtime_error("boom in input");
        return ClassifierInput::features;
    }
    SearchSpace search_space(std::size_t, std::size_t) const override {
        if (mode_ == 12) throw std::runtime_error("boom in search_space");
        return {};
    }
    Status train(const FeatureTable& data) override {
        if (mode_ == 9) throw std::runtime_error("boom in train");
        if (mode_ == 14) return {ErrorCode::invalid_argument, "refusing to train"};
        classes_ = data.class_names;
        means_.assign(classes_.size(), 0.0);
        std::vector<double> counts(classes_.size(), 0.0);
        for (std::size_t r = 0; r < data.rows; ++r) {
            const auto c = static_cast<std::size_t>(data.y[r]);
            means_[c] += data.row(r)[0];
            counts[c] += 1.0;
        }
        for (std::size_t c = 0; c < means_.size(); ++c) means_[c] /= std::max(counts[c], 1.0);
        return {};
    }
    Result<Prediction> predict(std::span<const double> x) const override {
        Prediction p;
        p.scores.assign(classes_.size(), 0.0);
        std::size_t best = 0;
        for (std::size_t c = 1; c < means_.size(); ++c)
            if (std::abs(x[0] - means_[c]) < std::abs(x[0] - means_[best])) best = c;
        p.label = static_cast<int>(best);
        p.class_name = classes_[best];
        p.scores[best] = 1.0;
        if (mode_ == 1) p.scores.assign(classes_.size(), std::numeric_limits<double>::quiet_NaN());
        if (mode_ == 2) p.scores = {0.0, 1.0};
        if (mode_ == 3) p.label = 99;
        if (mode_ == 4) p.class_name = "not-a-class";
        if (mode_ == 5) p.scores[best] = 7.0;
        if (mode_ == 6) {
            p.scores[best] = 1.5;
            p.scores[(best + 1) % p.scores.size()] = -0.5;
        }
        if (mode_ == 7) std::swap(p.scores[best], p.scores[(best + 1) % p.scores.size()]);
        if (mode_ == 8) throw std::runtime_error("boom in predict");
        return p;
    }
    std::vector<std::string> class_names() const override {
        if (mode_ == 13) throw std::runtime_error("boom in class_names");
        if (mode_ == 15) return {};
        return classes_;
    }
    Status save(const std::filesystem::path& file) const override {
        std::ofstream out(file);
        out << "rollsense-test-odd-scores mode " << mode_ << '\n';  // predict loads the model with default parameters
        for (std::size_t c = 0; c < classes_.size(); ++c) out << classes_[c] << ' ' << means_[c] << '\n';
        return out ? Status{} : Status{ErrorCode::io_error, file.string() + ": cannot write"};
    }
    Status load(const std::filesystem::path& file) override {
        std::ifstream in(file);
        std::string name, key;
        double mean = 0;
        if (!(in >> name >> key >> mode_) || name != "rollsense-test-odd-scores")
            return {ErrorCode::parse_error, file.string() + ": not a test_odd_scores model"};
        if (mode_ == 10) throw std::runtime_error("boom in load");
        classes_.clear();
        means_.clear();
        while (in >> name >> mean) {
            classes_.push_back(name);
            means_.push_back(mean);
        }
        if (classes_.empty()) return {ErrorCode::parse_error, file.string() + ": no classes"};
        return {};
    }

private:
    std::int64_t mode_ = 0;
    std::vector<std::string> classes_;
    std::vector<double> means_;
};
}  // namespace

ROLLSENSE_PLUGIN(OddScores, classifier, "test_odd_scores", "0.0.1", "test classifier whose predictions go wrong on demand",
                 odd_scores_schema)
