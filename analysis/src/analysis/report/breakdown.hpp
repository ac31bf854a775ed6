// Clean rates and accuracies split by rolling speed and by object. Accuracy
// comes from the out-of-fold predictions of the baseline's first repetition
// (one k-fold CV, as the paper ran), so every row is counted once.
#pragma once

#include <string>
#include <vector>

#include "rollsense/features.hpp"
#include "analysis/learn/evaluate.hpp"

namespace rollsense::report {

struct BreakdownRow {
    std::string label;
    std::size_t trials = 0, clean = 0;
    std::size_t evaluated = 0, correct = 0;  // clean trials with an out-of-fold prediction
    double clean_rate() const;
    double accuracy() const;  // NaN without evaluated trials
};

struct Breakdown {
    std::vector<BreakdownRow> by_speed;   // ascending speed
    std::vector<BreakdownRow> by_object;  // display order (the confusion matrix's)
};

// `trial_ids` are the evaluation's trials (Evaluation::trial_ids), in the
// order of report.baseline.first_predicted.
Breakdown breakdown(const std::vector<features::FeatureRow>& rows, const learn::EvaluationReport& report,
                    const std::vector<learn::ObjectShape>& catalogue, const std::vector<std::string>& trial_ids);

}  // namespace rollsense::report
