#include "analysis/learn/checked_classifier.hpp"

#include <cmath>

namespace rollsense::learn {

Status check_prediction(const Prediction& p, const std::vector<std::string>& class_names, const std::string& who) {
    const std::size_t classes = class_names.size();
    const std::string n = std::to_string(classes);
    if (p.label < 0 || static_cast<std::size_t>(p.label) >= classes)
        return {ErrorCode::plugin_error,
                who + " predicted label " + std::to_string(p.label) + " outside its " + n + " classes"};
    if (p.class_name != class_names[static_cast<std::size_t>(p.label)])
        return {ErrorCode::plugin_error, who + " named its label " + std::to_string(p.label) + " '" + p.class_name +
                                             "', which is class '" + class_names[static_cast<std::size_t>(p.label)] + "'"};
    if (p.scores.size() != classes)
        return {ErrorCode::plugin_error, who + " returned " + std::to_string(p.scores.size()) + " scores for " + n +
                                             " classes; a prediction has one score per class, in class order"};
    for (std::size_t c = 0; c < classes; ++c)
        if (!std::isfinite(p.scores[c]))
            return {ErrorCode::plugin_error, who + " returned a score that is not a finite number (" +
                                                 std::to_string(p.scores[c]) + ") for class " + std::to_string(c + 1) +
                                                 " of " + n};
    return {};
}

namespace {

class CheckedClassifier final : public Classifier {
public:
    CheckedClassifier(ClassifierPtr inner, std::string who) : inner_(std::move(inner)), who_(std::move(who)) {}

    ClassifierInput input() const override { return inner_->input(); }
    SearchSpace search_space(std::size_t rows, std::size_t cols) const override {
        return inner_->search_space(rows, cols);
    }
    Status train(const FeatureTable& data) override { return counted(inner_->train(data)); }
    Status load(const std::filesystem::path& file) override { return counted(inner_->load(file)); }
    Result<Prediction> predict(std::span<const double> features) const override {
        auto p = inner_->predict(features);
        if (!p) return p;
        if (auto s = check_prediction(*p, classes_, who_); !s) return s;
        return p;
    }
    std::vector<std::string> class_names() const override { return inner_->class_names(); }
    Status save(const std::filesystem::path& file) const override { return inner_->save(file); }
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override {
        return inner_->invoke(verb, args);
    }

private:
    // The classes predictions are checked against, once the model exists.
    Status counted(Status s) {
        if (s) classes_ = inner_->class_names();
        return s;
    }

    ClassifierPtr inner_;
    std::string who_;
    std::vector<std::string> classes_;
};

}  // namespace

ClassifierPtr checked_classifier(ClassifierPtr inner, std::string who) {
    return std::make_shared<CheckedClassifier>(std::move(inner), std::move(who));
}

}  // namespace rollsense::learn
