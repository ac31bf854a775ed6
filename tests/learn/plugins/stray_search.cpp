// A classifier plugin whose search_space() names a parameter ('depth') that
// its schema() does not declare, as a plugin written outside this repository
// might after renaming a parameter: `plugins --check` and `evaluate --optimize`
// must refuse it up front, naming the plugin and the parameter. Otherwise an
// honest classifier: the training set's class frequencies, smoothed.
#include <algorithm>
#include <fstream>

#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

ParamSchema stray_search_schema() {
    return {param_number("smoothing", 1.0, "added to every class's count", 0.0, 10.0)};
}

class StraySearch final : public Classifier {
public:
    Status on_configure(const ParamSet& p, const PluginContext&) override {
        smoothing_ = p.get_number("smoothing");
        return {};
    }
    SearchSpace search_space(std::size_t, std::size_t) const override {
        using Scale = SearchDimension::Scale;
        return {{"smoothing", Scale::real_linear, 0.0, 10.0, {}}, {"depth", Scale::integer_linear, 1, 8, {}}};
    }
    Status train(const FeatureTable& data) override {
        classes_ = data.class_names;
        scores_.assign(classes_.size(), smoothing_);
        for (int y : data.y) scores_[static_cast<std::size_t>(y)] += 1.0;
        double sum = 0.0;
        for (double s : scores_) sum += s;
        for (double& s : scores_) s = sum > 0 ? s / sum : 1.0 / static_cast<double>(scores_.size());
        return {};
    }
    Result<Prediction> predict(std::span<const double>) const override {
        Prediction p;
        p.scores = scores_;
        p.label = static_cast<int>(std::max_element(scores_.begin(), scores_.end()) - scores_.begin());
        p.class_name = classes_[static_cast<std::size_t>(p.label)];
        return p;
    }
    std::vector<std::string> class_names() const override { return classes_; }
    Status save(const std::filesystem::path& file) const override {
        std::ofstream out(file);
        for (std::size_t c = 0; c < classes_.size(); ++c) out << classes_[c] << ' ' << scores_[c] << '\n';
        return out ? Status{} : Status{ErrorCode::io_error, file.string() + ": cannot write"};
    }
    Status load(const std::filesystem::path& file) override {
        std::ifstream in(file);
        classes_.clear();
        scores_.clear();
        std::string name;
        for (double s = 0; in >> name >> s;) {
            classes_.push_back(name);
            scores_.push_back(s);
        }
        if (classes_.empty()) return {ErrorCode::parse_error, file.string() + ": not a test_stray_search model"};
        return {};
    }

private:
    double smoothing_ = 1.0;
    std::vector<std::string> classes_;
    std::vector<double> scores_;
};
}  // namespace

ROLLSENSE_PLUGIN(StraySearch, classifier, "test_stray_search", "0.0.1",
                 "test classifier whose search space names a parameter its schema lacks", stray_search_schema)
