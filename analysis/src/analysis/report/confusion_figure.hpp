// The confusion matrix as the paper's Fig. 9: counts in cells shaded by the
// share of their true class, a true-positive-rate column on the right, and
// thick lines around the blocks of cylinders, large and small polygons.
#pragma once

#include <string>
#include <vector>

#include "analysis/learn/metrics.hpp"
#include "analysis/learn/paper_analysis.hpp"

namespace rollsense::report {

// `id` becomes the <svg> id; `caption` its title.
std::string confusion_figure(const learn::ConfusionMatrix& matrix, const std::vector<learn::ObjectShape>& catalogue,
                             const std::string& id, const std::string& caption);

}  // namespace rollsense::report
