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

Result<RunConfig> read_run_config(const fs::path& dir) {
    std::error_code ec;
    if (!fs::exists(dir / kRunConfigFile, ec)) return RunConfig{};
    auto reader = csv::Reader::open(dir / kRunConfigFile);
    if (!reader) return reader.error();
    auto key = reader->column("key");
    if (!key) return key.error();
    auto value = reader->column("value");
    if (!value) return value.error();
    RunConfig config;
    std::vector<std::string> f;
    for (;;) {
        auto more = reader->next(f);
        if (!more) return more.error();
        if (!*more) break;
        config.emplace_back(f[*key], f[*value]);
    }
    return config;
}

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
