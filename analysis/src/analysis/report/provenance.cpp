#include "analysis/report/provenance.hpp"

#include <ctime>

#include "rollsense/csv.hpp"

namespace rollsense::report {

Result<KeyValues> read_run_info(const std::filesystem::path& dataset_dir) {
    const auto file = dataset_dir / "run-info.csv";
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return KeyValues{};
    auto reader = csv::Reader::open(file);
    if (!reader) return reader.error();
    auto key = reader->column("key");
    if (!key) return key.error();
    auto value = reader->column("value");
    if (!value) return value.error();
    KeyValues out;
    std::vector<std::string> fields;
    for (;;) {
        auto more = reader->next(fields);
        if (!more) return more.error();
        if (!*more) break;
        out.emplace_back(fields[*key], fields[*value]);
    }
    return out;
}

std::string utc_timestamp() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

}  // namespace rollsense::report
