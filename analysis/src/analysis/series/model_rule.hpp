// The series rule a model was trained with, as the one line of text its model
// file keeps (FeatureTable::series_rule, Classifier::series_rule()), so that
// predict, clf:identify() and the prefix models prepare a recording exactly as
// training did (docs/series-preparation.md, "Recorded in the model").
//
//   length=128 detect_window=5 contact_fraction=0.1 noise_floor=0.01 min_amplitude=0.03 margin=0.1
//   require_complete_contact=true amplitude=global_scale scale=1 z_floor=0.01 max_invalid_fraction=0.1
//   max_gap=5 time_axis=contact                                                         (one line)
//
// Every setting that shapes the prepared row is written; `prefix` and
// `open_end` are not: they say how much of one recording is used (training a
// prefix model, identifying during the roll), not how it is prepared. The
// classifier plugins store the text without reading it: this file is its one
// home.
#pragma once

#include <string>
#include <string_view>

#include "analysis/series/prepare.hpp"
#include "rollsense/classifier.hpp"

namespace rollsense::series {

// `settings` as "key=value ..." (numbers in the shortest form that reads back exactly).
std::string rule_text(const SeriesSettings& settings);

// rule_text's text back to settings. A key left out keeps its default; an
// unknown or repeated key, a malformed value or settings out of range are an
// error naming `source` (the model file) and the key.
Result<SeriesSettings> parse_rule_text(std::string_view text, const std::string& source);

// Marks `table` as series prepared with `settings`: its series_length and series_rule.
void describe_series(FeatureTable& table, const SeriesSettings& settings);

// The rule a trained or loaded series model was trained with. `recorded` is
// false for a model file written before rollsense recorded the rule: its
// settings are then the defaults (the caller knows the model's length).
struct ModelRule {
    SeriesSettings settings;
    bool recorded = false;
};
Result<ModelRule> model_rule(const Classifier& model, const std::string& source);

}  // namespace rollsense::series
