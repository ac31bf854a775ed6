#include "analysis/report/provenance.hpp"

#include <ctime>

#include "rollsense/csv.hpp"
#include "rollsense/run_config.hpp"

namespace rollsense::report {

Result<KeyValues> read_run_info(const std::filesystem::path& dataset_dir) {
    return csv::read_key_values(dataset_dir / kRunInfoFile);
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
