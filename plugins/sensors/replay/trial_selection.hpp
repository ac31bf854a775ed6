// Which recorded trial a replay plays: the one matching the script's trial
// (by id, else by object/speed/repetition), the next one in manifest order, or
// one the script pinned with device:call("select", {...}).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/status.hpp"

namespace rollsense::plugins::replay {

// What a script asks for. Empty fields are not compared.
struct TrialQuery {
    std::string id;
    std::string object;
    std::string speed;
    std::optional<int> repetition;
    std::optional<std::size_t> index;  // 0-based position in the manifest

    bool empty() const { return id.empty() && object.empty() && speed.empty() && !repetition && !index; }
    // "trial 'C1-v10-r001'", "object C1, speed 10, repetition 3", "trial #4"
    std::string describe() const;
};

// Speeds are labels ("10") but a hand-made manifest may write "10.0": equal
// text, or equal numbers when both parse as numbers.
bool same_speed(const std::string& a, const std::string& b);

// The manifest row the query names. With an id, the id decides; otherwise
// every given field must match and the first such row in manifest order wins.
// `dataset` names the folder in the error, which lists what the dataset holds.
Result<std::size_t> find_trial(const std::vector<TrialRecord>& trials, const TrialQuery& query,
                               const std::string& dataset);

// The trial for a script's rs.trial{...}: by id first (the ids rs.trial makes
// are "<object>-v<speed>-r<repetition>", so a recording replays under the same
// script), then by object/speed/repetition when the script names its trials
// differently.
Result<std::size_t> match_script_trial(const std::vector<TrialRecord>& trials, const TrialInfo& trial,
                                       const std::string& dataset);

}  // namespace rollsense::plugins::replay
