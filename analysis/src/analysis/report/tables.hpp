// The report's tables as HTML fragments. Every number is labelled with how it
// was obtained (which CV, pooled or per repetition, optimistic or honest).
#pragma once

#include <string>
#include <vector>

#include "analysis/learn/evaluate.hpp"
#include "analysis/report/breakdown.hpp"
#include "analysis/report/provenance.hpp"

namespace rollsense::report {

// Accuracy of the preset: mean ± sd over repetitions, pooled Wilson interval. `trials_word`: what the trials used are
// called (learn::used_trials_word).
std::string accuracy_table(const learn::EvaluationReport& report, const std::string& classifier,
                           const std::string& trials_word);
std::string breakdown_table(const std::vector<BreakdownRow>& rows, const std::string& what,
                            const learn::ConfusionMatrix* pooled);
// method.md §6: each of the paper's analyses for this data, beside the paper's
// number; `extra` rows come from elsewhere (e.g. the recording's durations).
struct ExtraRow {
    std::string label, ours, paper;
};
std::string paper_comparison_table(const learn::PaperAnalysis& ours, const std::vector<ExtraRow>& extra = {});
// The parameters used, and with tuning the ones the optimiser chose (per outer fold for nested CV).
std::string hyperparameter_table(const learn::EvaluationReport& report);
// Preset CV, tuned-on-the-same-folds (optimistic) and nested CV side by side.
std::string protocol_table(const learn::EvaluationReport& report);
std::string key_value_table(const KeyValues& entries);

std::string format_param(const ParamValue& value);
// "74.9 ± 0.9 %" (fractions in, percent out), or with one repetition
// "74.9 % (one repetition: no spread)" (learn::has_spread).
std::string mean_sd(double mean, double sd);

}  // namespace rollsense::report
