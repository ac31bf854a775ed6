// A classifier plugin whose declarations are wrong, as a plugin written outside this repository might get them
// (built once per mistake, tests/learn/CMakeLists.txt): `plugins --check` and `evaluate --optimize` must refuse it up
// front, naming the plugin and the way out.
//   STRAY_MISTAKE_stray_search: search_space() names a parameter ('depth') schema() does not declare (renamed, say);
//   STRAY_MISTAKE_wide_search: search_space() searches 'smoothing' up to 50, which schema() caps at 10;
//   STRAY_MISTAKE_crooked_search: search_space() searches its integer 'neighbours' on a real scale;
//   STRAY_MISTAKE_throwing_configure: configuring it (with its defaults too) throws;
//   STRAY_MISTAKE_refusing_configure: on_configure refuses its own defaults (an error status).
// Otherwise an honest classifier: the training set's class frequencies, smoothed.
#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "rollsense/plugin.hpp"

namespace {
using namespace rollsense;

ParamSchema stray_search_schema() {
    return {param_number("smoothing", 1.0, "added to every class's count", 0.0, 10.0),
#ifdef STRAY_MISTAKE_crooked_search
            param_int("neighbours", 3, "unused: an integer to search", 1, 9),
#endif
    };
}

class StraySearch final : public Classifier {
public:
    Status on_configure(const ParamSet& p, const PluginContext&) override {
#ifdef STRAY_MISTAKE_throwing_configure
        throw std::runtime_error("no licence file found");
#endif
#ifdef STRAY_MISTAKE_refusing_configure
        if (p.get_number("smoothing") == 1.0) return {ErrorCode::invalid_argument, "smoothing 1 is not supported"};
#endif
        smoothing_ = p.get_number("smoothing");
        return {};
    }
    SearchSpace search_space(std::size_t, std::size_t) const override {
        using Scale = SearchDimension::Scale;
#ifdef STRAY_MISTAKE_stray_search
        return {{"smoothing", Scale::real_linear, 0.0, 10.0, {}}, {"depth", Scale::integer_linear, 1, 8, {}}};
#elif defined(STRAY_MISTAKE_crooked_search)
        return {{"smoothing", Scale::real_linear, 0.0, 10.0, {}}, {"neighbours", Scale::real_linear, 1, 9, {}}};
#else
        return {{"smoothing", Scale::real_linear, 0.0, 50.0, {}}};
#endif
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

ROLLSENSE_PLUGIN(StraySearch, classifier, STRAY_NAME, "0.0.1", "test classifier whose declarations are wrong",
                 stray_search_schema)
