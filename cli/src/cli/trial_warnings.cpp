#include "cli/trial_warnings.hpp"

#include <algorithm>
#include <string>

#include "rollsense/log.hpp"

namespace rollsense::cli {
namespace {
constexpr std::string_view kUnreadable = "unreadable (";

bool unreadable(const features::FeatureRow& r) { return !r.clean && r.reason.starts_with(kUnreadable); }

// The reader's words inside "unreadable (...)".
std::string why_unreadable(const features::FeatureRow& r) {
    std::string why = r.reason.substr(kUnreadable.size());
    if (!why.empty() && why.back() == ')') why.pop_back();
    return why;
}
}  // namespace

Status warn_unreadable_trials(const std::vector<features::FeatureRow>& rows) {
    // Every file failing alike is the dataset's fault, said once (review: 81 warnings blamed the trial files for a
    // channel that dataset-info.csv named wrongly, and the command went on to exit 0).
    if (!rows.empty() && std::all_of(rows.begin(), rows.end(), unreadable))
        return {ErrorCode::parse_error, "none of the " + std::to_string(rows.size()) + " trials could be read; the "
                                            "first, '" + rows.front().trial_id + "': " + why_unreadable(rows.front()) +
                                            ". When every file fails alike, check dataset-info.csv (its channels) "
                                            "against the trial files' header; otherwise repair or restore the files "
                                            "(in a dataset a run recorded, that run's command line plus --resume "
                                            "records them again)"};
    for (const auto& r : rows)
        if (unreadable(r))
            log_warning("rollsense", "trial '" + r.trial_id + "' left out: " + why_unreadable(r) +
                                         "; repair or restore the file (in a dataset a run recorded, that run's "
                                         "command line plus --resume records it again)");
    return {};
}

}  // namespace rollsense::cli
