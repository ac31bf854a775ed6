// The default id of a trial, in one place: `<object>-v<speed>-r<repetition>`
// with the repetition zero-padded to three digits, e.g. "C1-v10-r007".
// rs.trial{} gives it to a trial that names no id, and scripts that need an id
// before the trial exists (--resume's rs.has_trial) ask rs.trial_id{} for the
// same string; docs/dataset-format.md ("manifest.csv") documents it.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "rollsense/status.hpp"
#include "rollsense/types.hpp"

namespace rollsense {

// `speed` as the script wrote it ("10", "12.5"): the id keeps its spelling.
std::string trial_id(std::string_view object, std::string_view speed, int repetition);

// A trial id names its file (trials/<id>.csv) on every filesystem a dataset
// may be copied to, so it is checked before anything is written: 1 to
// kMaxTrialIdLength characters of [A-Za-z0-9._-], not starting with '.', and
// not a name Windows reserves (CON, NUL, COM1, ...). An error says which rule
// the id breaks and how to name it.
inline constexpr std::size_t kMaxTrialIdLength = 100;
Status check_trial_id(std::string_view id);

// The paper's protocol (one mounting of a specimen on the winch, rolled many
// times): which mounting a roll belongs to and how many rolls of it came
// before. A script gives them as trial metadata (etroll.run_trial{mount=,
// index_in_mount=}, in TrialInfo::extra); the manifest holds them in columns
// of their own, so that MATLAB or pandas group by them without parsing
// `extra`. Reading puts them back among the metadata.
inline const std::array<std::string, 2> kProtocolKeys = {"mount", "index_in_mount"};

// A trial's id (check_trial_id) and its extras, which the manifest's `extra`
// column ("key=value;key=value") must give back as they were: a key is not
// empty and holds no '=' or ';', a value holds no ';' (a protocol key's value
// may: it has a column of its own).
Status check_trial_info(const TrialInfo& info);

}  // namespace rollsense
