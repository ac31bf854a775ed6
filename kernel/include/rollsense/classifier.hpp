// Classifier plugin interface: trained on a feature table, predicts a class
// with per-class scores, saves and loads its model.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "rollsense/component.hpp"

namespace rollsense {

// Rows are trials, columns features; row-major for cheap row access.
struct FeatureTable {
    std::vector<std::string> feature_names;
    std::vector<std::string> class_names;  // label i is class_names[i]
    std::size_t rows = 0;
    std::vector<double> x;                 // rows * feature_names.size()
    std::vector<int> y;                    // rows labels in [0, class_names.size())

    std::size_t cols() const { return feature_names.size(); }
    std::span<const double> row(std::size_t i) const { return {x.data() + i * cols(), cols()}; }
};

struct Prediction {
    int label = -1;
    std::string class_name;
    std::vector<double> scores;  // one per class, summing to 1 (posterior estimate)
};

class ROLLSENSE_API Classifier : public Component {
public:
    virtual Status train(const FeatureTable& data) = 0;
    virtual Result<Prediction> predict(std::span<const double> features) const = 0;
    virtual std::vector<std::string> class_names() const = 0;
    virtual Status save(const std::filesystem::path& file) const = 0;
    virtual Status load(const std::filesystem::path& file) = 0;
};

}  // namespace rollsense
