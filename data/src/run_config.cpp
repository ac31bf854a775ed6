#include "rollsense/run_config.hpp"

#include <algorithm>
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

bool run_killed_before_end(const fs::path& dir) {
    std::error_code ec;
    return fs::exists(dir / kRunConfigFile, ec) && !fs::exists(dir / kRunInfoFile, ec);
}

bool is_read_file_key(std::string_view key) { return key.starts_with("module.") || key.starts_with("include."); }

bool lists_read_files(const RunConfig& config) {
    return std::ranges::any_of(config, [](const auto& row) { return is_read_file_key(row.first); });
}

std::vector<std::string> run_config_differences(const RunConfig& recorded, const RunConfig& now) {
    std::map<std::string, std::pair<const std::string*, const std::string*>> both;
    for (const auto& [k, v] : recorded) both[k].first = &v;
    for (const auto& [k, v] : now) both[k].second = &v;
    auto same = [&](const std::string& key) {
        const auto it = both.find(key);
        return it != both.end() && it->second.first && it->second.second && *it->second.first == *it->second.second;
    };
    const bool recorded_before_rows = !lists_read_files(recorded);
    std::vector<std::string> out;
    for (const auto& [k, values] : both) {
        // A profile file is compared by its content: "./hand.lua" and "/lab/hand.lua" are one profile.
        if (same(k) || (k == "profile" && same("profile_fnv1a"))) continue;
        const auto& [was, is] = values;
        // A module or included profile is listed by name. A dataset that lists none predates these rows; otherwise
        // one the recording did not list is a difference too (diff review: a pcall(require) that failed then).
        const bool read_file = is_read_file_key(k);
        if (read_file && !was && recorded_before_rows) continue;
        // A hash is no reason a user reads (review): say what it means.
        // Only where the file is the same one (second review: another --profile was said to be edited).
        std::string file = k == "script_fnv1a" ? "script" : k == "profile_fnv1a" ? "profile" : "";
        if (read_file) {  // "module.lib.helper_fnv1a": the module lib.helper
            const auto dot = k.find('.');
            file = (k.starts_with("module.") ? "module " : "included profile ") + k.substr(dot + 1, k.size() - dot - 7);
        }
        const std::string edited = !file.empty() && (read_file ? was && is : same(file))
                                       ? " (the " + file + " was edited since it recorded: restore it, or record anew "
                                                           "into another --out)"
                                       : "";
        out.push_back(k + ": recorded " + (was ? "'" + *was + "'" : "(not given)") + ", this run " +
                      (is ? "'" + *is + "'" : "(not given)") + edited);
    }
    return out;
}

Status check_resume_config(const fs::path& dir, const RunConfig& now) {
    auto recorded = read_run_config(dir);
    if (!recorded) {  // review: an empty or damaged file was named with no way on
        const std::string way = recorded.error().code != ErrorCode::parse_error
                                    ? ""
                                    : "; repair or restore it (run-info.csv's command_line shows the run that "
                                      "recorded the dataset), or record anew into another --out";
        return Error{recorded.error().code, "cannot resume: " + recorded.error().message + way};
    }
    std::string text;
    if (!recorded->empty() && !now.empty())
        for (const auto& d : run_config_differences(*recorded, now)) text += "\n  " + d;
    if (text.empty()) return {};
    return {ErrorCode::invalid_argument, "cannot resume " + dir.string() + ": this run differs from the one that recorded it (" +
                                             (dir / kRunConfigFile).string() + "):" + text +
                                             "\nresume with the same script, --profile, --set options and --seed, or "
                                             "choose another folder with --out"};
}

}  // namespace rollsense
