#include "rollsense/run_config.hpp"

#include <map>

#include "rollsense/csv.hpp"

namespace rollsense {
namespace fs = std::filesystem;

std::string format_run_config(const RunConfig& config) {
    std::string out;
    csv::append_row(out, {"key", "value"});
    for (const auto& [k, v] : config) csv::append_row(out, {k, v});
    return out;
}

Result<RunConfig> read_run_config(const fs::path& dir) { return csv::read_key_values(dir / kRunConfigFile); }

std::vector<std::string> run_config_differences(const RunConfig& recorded, const RunConfig& now) {
    std::map<std::string, std::pair<const std::string*, const std::string*>> both;
    for (const auto& [k, v] : recorded) both[k].first = &v;
    for (const auto& [k, v] : now) both[k].second = &v;
    std::vector<std::string> out;
    for (const auto& [k, values] : both) {
        const auto& [was, is] = values;
        if (was && is && *was == *is) continue;
        out.push_back(k + ": recorded " + (was ? "'" + *was + "'" : "(not given)") + ", this run " +
                      (is ? "'" + *is + "'" : "(not given)"));
    }
    return out;
}

}  // namespace rollsense
