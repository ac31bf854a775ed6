// Several classifiers evaluated on the same folds, side by side: accuracy
// table, per-class accuracy, the paired per-fold differences as a table and a
// figure, and one confusion matrix per classifier. Shown only when the
// evaluation compares more than one classifier.
#pragma once

#include <string>
#include <vector>

#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/paper_analysis.hpp"

namespace rollsense::report {

// The section's body (tables and figures, HTML).
std::string comparison_section(const learn::Evaluation& evaluation, const std::vector<learn::ObjectShape>& catalogue);

// The paired per-fold differences, one row per pair: every fold's difference
// as a dot, the mean as a bar with ± 1 sd, and the zero line.
std::string paired_difference_figure(const learn::Evaluation& evaluation, const std::string& id);

}  // namespace rollsense::report
