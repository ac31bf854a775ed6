#include "rollsense/dataset_files.hpp"

#include "rollsense/run_config.hpp"
#include "rollsense/shard.hpp"

namespace rollsense {
namespace fs = std::filesystem;

bool is_dataset_file(std::string_view name) {
    for (const char* own : {"manifest.csv", "dataset-info.csv", kRunInfoFile, "trials", kRunConfigFile,
                            kShardPlanFile, kShardsFile})
        if (name == own) return true;
    return earlier_run_number(name) > 0;
}

std::string earlier_run_info_name(std::size_t n) { return "run-info." + std::to_string(n) + ".csv"; }

std::size_t earlier_run_number(std::string_view name) {
    constexpr std::string_view head = "run-info.", tail = ".csv";
    if (name.size() <= head.size() + tail.size() || !name.starts_with(head) || !name.ends_with(tail)) return 0;
    const auto digits = name.substr(head.size(), name.size() - head.size() - tail.size());
    if (digits.size() > 9 || digits[0] == '0') return 0;
    std::size_t n = 0;
    for (char c : digits) {
        if (c < '0' || c > '9') return 0;
        n = n * 10 + static_cast<std::size_t>(c - '0');
    }
    return n;
}

bool holds_dataset(const fs::path& dir) {
    std::error_code ec;
    return fs::exists(dir / "manifest.csv", ec) || fs::exists(dir / "dataset-info.csv", ec);
}

Status check_no_dataset_in(const fs::path& dir) {
    if (!holds_dataset(dir)) return {};
    return {ErrorCode::invalid_argument,
            dir.string() + " already holds a dataset; continue it with --resume, or choose another folder with --out"};
}

Status check_not_dataset_file(const fs::path& target, const fs::path& dataset_dir, std::string_view what) {
    std::error_code ec;
    const fs::path dir = fs::weakly_canonical(dataset_dir, ec);
    if (ec) return {};  // no such folder: nothing of it to overwrite
    const fs::path file = fs::weakly_canonical(target, ec);
    if (ec) return {};
    // The first part of `file` below `dir`, if `file` is inside it at all.
    auto rel = file.lexically_relative(dir);
    if (rel.empty() || *rel.begin() == ".." || *rel.begin() == ".") return {};
    const std::string first = rel.begin()->string();
    if (!is_dataset_file(first)) return {};
    return {ErrorCode::invalid_argument,
            std::string(what) + " " + target.string() + " is " +
                (first == "trials" ? "under the trials/ folder" : "the file " + first) + " of the dataset " +
                dataset_dir.string() + "; writing it would destroy the dataset: give " + std::string(what) +
                " a file outside the dataset, or one of another name"};
}

}  // namespace rollsense
