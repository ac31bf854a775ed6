#include "trial_selection.hpp"

#include <charconv>

namespace rollsense::plugins::replay {

namespace {

std::optional<double> as_number(const std::string& text) {
    double v = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
    return v;
}

bool matches(const TrialRecord& r, const TrialQuery& q) {
    if (!q.object.empty() && r.info.object != q.object) return false;
    if (!q.speed.empty() && !same_speed(r.info.speed, q.speed)) return false;
    if (q.repetition && r.info.repetition != *q.repetition) return false;
    return true;
}

// "it holds 1350 trials: C1-v10-r001, C1-v10-r002, … (see manifest.csv)"
std::string holdings(const std::vector<TrialRecord>& trials) {
    std::string out = "it holds " + std::to_string(trials.size()) + " trial" + (trials.size() == 1 ? "" : "s");
    if (trials.empty()) return out;
    out += ": ";
    const std::size_t shown = std::min<std::size_t>(trials.size(), 6);
    for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + trials[i].info.id;
    if (shown < trials.size()) out += ", ... (see manifest.csv)";
    return out;
}

}  // namespace

std::string TrialQuery::describe() const {
    if (!id.empty()) return "trial '" + id + "'";
    if (index) return "trial #" + std::to_string(*index + 1) + " of the manifest";
    std::string out;
    auto add = [&](const std::string& s) { out += (out.empty() ? "" : ", ") + s; };
    if (!object.empty()) add("object " + object);
    if (!speed.empty()) add("speed " + speed);
    if (repetition) add("repetition " + std::to_string(*repetition));
    return out.empty() ? "any trial" : out;
}

bool same_speed(const std::string& a, const std::string& b) {
    if (a == b) return true;
    auto x = as_number(a), y = as_number(b);
    return x && y && *x == *y;
}

Result<std::size_t> find_trial(const std::vector<TrialRecord>& trials, const TrialQuery& query,
                               const std::string& dataset) {
    if (query.index) {
        if (*query.index < trials.size()) return *query.index;
        return Error{ErrorCode::not_found, "dataset " + dataset + " has no " + query.describe() + "; " +
                                               holdings(trials)};
    }
    for (std::size_t i = 0; i < trials.size(); ++i) {
        if (!query.id.empty() ? trials[i].info.id == query.id : matches(trials[i], query)) return i;
    }
    return Error{ErrorCode::not_found, "dataset " + dataset + " has no " + query.describe() + "; " + holdings(trials)};
}

Result<std::size_t> match_script_trial(const std::vector<TrialRecord>& trials, const TrialInfo& trial,
                                       const std::string& dataset) {
    TrialQuery by_id;
    by_id.id = trial.id;
    if (auto i = find_trial(trials, by_id, dataset); i) return i;
    TrialQuery by_fields;
    by_fields.object = trial.object;
    by_fields.speed = trial.speed;
    by_fields.repetition = trial.repetition;
    if (!by_fields.object.empty())
        if (auto i = find_trial(trials, by_fields, dataset); i) return i;
    return Error{ErrorCode::not_found,
                 "dataset " + dataset + " has no trial for the script's trial '" + trial.id + "' (object " +
                     trial.object + ", speed " + trial.speed + ", repetition " + std::to_string(trial.repetition) +
                     "); " + holdings(trials)};
}

}  // namespace rollsense::plugins::replay
