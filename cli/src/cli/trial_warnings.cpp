#include "cli/trial_warnings.hpp"

#include <string>

#include "rollsense/log.hpp"

namespace rollsense::cli {

void warn_unreadable_trials(const std::vector<features::FeatureRow>& rows) {
    const std::string prefix = "unreadable (";
    for (const auto& r : rows) {
        if (r.clean || r.reason.rfind(prefix, 0) != 0) continue;
        std::string why = r.reason.substr(prefix.size());
        if (!why.empty() && why.back() == ')') why.pop_back();
        log_warning("rollsense", "trial '" + r.trial_id + "' left out: " + why +
                                     "; repair or restore the file (a run records it again with its command line "
                                     "plus --resume)");
    }
}

}  // namespace rollsense::cli
