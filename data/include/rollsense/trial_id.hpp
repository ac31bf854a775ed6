// The default id of a trial, in one place: `<object>-v<speed>-r<repetition>`
// with the repetition zero-padded to three digits, e.g. "C1-v10-r007".
// rs.trial{} gives it to a trial that names no id, and scripts that need an id
// before the trial exists (--resume's rs.has_trial) ask rs.trial_id{} for the
// same string; docs/dataset-format.md ("manifest.csv") documents it.
#pragma once

#include <string>
#include <string_view>

namespace rollsense {

// `speed` as the script wrote it ("10", "12.5"): the id keeps its spelling.
std::string trial_id(std::string_view object, std::string_view speed, int repetition);

}  // namespace rollsense
