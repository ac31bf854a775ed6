// The conformance suite must fail a classifier whose predicted class is not the one it scores highest: the program
// refuses such predictions (analysis/learn/checked_classifier.cpp), and a plugin review found the suite passed one.
// Run by ctest expecting the suite's own message (PASS_REGULAR_EXPRESSION); its exit status is a failure.
#include <catch2/catch.hpp>

#include "rollsense/nearest_centroid/nearest_centroid.hpp"
#include "rollsense/testing/classifier_conformance.hpp"
#include "temp_dir.hpp"

namespace {

// nearest_centroid with its scores rotated by one class: a distribution, summing to 1, but the label is not the top.
class RotatedScores : public rollsense::Classifier {
public:
    rollsense::Status on_configure(const rollsense::ParamSet& params, const rollsense::PluginContext& context) override {
        return inner_.on_configure(params, context);
    }
    rollsense::Status train(const rollsense::FeatureTable& data) override { return inner_.train(data); }
    rollsense::Result<rollsense::Prediction> predict(std::span<const double> features) const override {
        auto p = inner_.predict(features);
        if (p) std::rotate(p->scores.begin(), p->scores.begin() + 1, p->scores.end());
        return p;
    }
    std::vector<std::string> class_names() const override { return inner_.class_names(); }
    rollsense::Status save(const std::filesystem::path& file) const override { return inner_.save(file); }
    rollsense::Status load(const std::filesystem::path& file) override { return inner_.load(file); }

private:
    rollsense::nearest_centroid::NearestCentroid inner_;
};

}  // namespace

TEST_CASE("the classifier conformance suite fails a label that is not the top score", "[conformance]") {
    rollsense::testing::TempDir dir("conformance-catches-label");
    rollsense::testing::ClassifierConformance c;
    c.name = "nearest_centroid";
    c.make = [] { return std::make_unique<RotatedScores>(); };
    c.schema = rollsense::nearest_centroid::nearest_centroid_schema();
    c.scratch = dir.path();
    rollsense::testing::check_classifier_conformance(c);
}
