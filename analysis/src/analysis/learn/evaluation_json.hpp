// evaluation.json: the in-memory Evaluation as a machine-readable file for
// scripts and notebooks (schema: docs/evaluation-json.md). Rendered from the
// same Evaluation as the terminal summary, evaluation.txt and the report.
#pragma once

#include <string>

#include "analysis/learn/evaluate.hpp"

namespace rollsense::learn {

// Bumped whenever a field changes meaning or disappears (additions keep it).
inline constexpr int kEvaluationJsonVersion = 2;  // 2: prefixes are cut on the contact's own clock (docs/evaluation-json.md)

std::string evaluation_json(const Evaluation& evaluation);

}  // namespace rollsense::learn
