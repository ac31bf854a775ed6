#include "cli/run_dataset.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "rollsense/atomic_file.hpp"
#include "rollsense/checksum.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/dataset_files.hpp"

namespace rollsense::cli {
namespace fs = std::filesystem;

namespace {
std::string file_digest(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return "(unreadable)";
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return fnv1a_hex(bytes.str());
}
}  // namespace

RunConfig run_config_of(const fs::path& script, const std::string& profile, const fs::path& profile_file,
                        std::uint64_t seed, const SetOptions& sets) {
    RunConfig config{{"rollsense_version", ROLLSENSE_VERSION_STRING},
                     {"script", script.filename().string()},
                     {"script_fnv1a", file_digest(script)},
                     {"profile", profile},
                     {"profile_fnv1a", file_digest(profile_file)},
                     {"seed", std::to_string(seed)}};
    std::map<std::string, std::string> last;
    for (const auto& [key, value] : sets) last[key] = value;
    for (const auto& [key, value] : last) config.emplace_back("set." + key, value);
    return config;
}

std::string shell_quote(const std::string& text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("_-./=,:+@%").find(c) != std::string_view::npos;
    });
    if (plain) return text;
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string resume_command(const std::string& script, const fs::path& out,
                           const std::vector<std::pair<std::string, std::string>>& options) {
    std::string line = "rollsense run " + shell_quote(script) + " --out " + shell_quote(out.string()) + " --resume";
    for (const auto& [option, value] : options) line += " " + option + " " + shell_quote(value);
    return line;
}

std::size_t trials_listed(const fs::path& dir) {
    auto dataset = DatasetReader::open(dir, DatasetReader::MissingTrialFile::keep_listed);
    return dataset ? dataset->trials().size() : 0;
}

std::string analysis_commands(const fs::path& dataset, const fs::path& out) {
    const std::string in = shell_quote(dataset.string());
    const bool beside = dataset.lexically_normal() == out.lexically_normal();  // report's default: DATASET/report.html
    return "rollsense report " + in + (beside ? "" : " -o " + shell_quote((out / "report.html").string())) +
           "; rollsense train " + in + " -o " + shell_quote((out / "model.rsm").string());
}

namespace {
// A shard's resume: the folder's shard (run-info.csv) against --shard.
Status check_resumed_shard(const fs::path& dir, const std::optional<Shard>& shard) {
    std::error_code ec;
    std::optional<std::string> recorded;  // "K/N"; empty: a whole run; none: not known
    if (fs::exists(dir / "run-info.csv", ec)) {
        auto info = csv::read_key_values(dir / "run-info.csv");
        if (!info)  // the dataset's error (3, or 5), not the command line's; provenance only, so it can be moved aside
            return Error{info.error().code, "cannot resume " + dir.string() + ": its run-info.csv names the shard it "
                                            "holds and cannot be read (" + info.error().message + "); move it aside "
                                            "(e.g. to run-info.damaged.csv) and resume again"};
        recorded = "";
        for (const auto& [key, value] : *info)
            if (key == "shard") recorded = value;
    }
    if (fs::exists(dir / kShardPlanFile, ec) && (!recorded || recorded->empty()))
        recorded = "K/N";  // a shard's plan without its record: which shard is not known
    // A shard writes its run-info.csv when it starts, a whole run when it ends: a run's folder (run-config.csv)
    // without one is a whole run killed before its end (review: it was resumed as a shard, mixing the two).
    if (!recorded && fs::exists(dir / kRunConfigFile, ec)) recorded = "";
    const std::string asked = shard ? shard->text() : std::string();
    // A shard's plan without the run-info.csv that names the shard: any --shard is taken at its word.
    if (!recorded || *recorded == asked || (*recorded == "K/N" && !asked.empty())) return {};
    const std::string merge = "; to analyse the whole run, join its shards with 'rollsense merge OUT SHARD...' "
                              "and resume OUT (docs/cluster.md)";
    if (recorded->empty())
        return {ErrorCode::invalid_argument, "cannot resume " + dir.string() + " with --shard " + asked +
                                                 ": it holds a whole run (its run-info.csv names no shard, or it has none: a whole run killed before "
                                                 "its end); "
                                                 "resume it without --shard"};
    const std::string holds = "cannot resume " + dir.string() + (asked.empty() ? "" : " as --shard " + asked) +
                              ": it holds shard " + *recorded + " of a run (" +
                              (dir / (*recorded == "K/N" ? kShardPlanFile : "run-info.csv")).string() + ")";
    if (*recorded == "K/N")
        return {ErrorCode::invalid_argument, holds + ", whose run-info.csv (naming which shard) is missing; resume it with "
                                                     "the --shard it was recorded with" + merge};
    return {ErrorCode::invalid_argument, holds + "; resume it with --shard " + *recorded + merge};
}
}  // namespace

Status check_out_folder(const fs::path& dir, bool resume, const std::optional<Shard>& shard) {
    if (auto s = check_can_be_folder(dir); !s)
        return {ErrorCode::invalid_argument, "--out " + s.message() +
                                                 " (choose a new or empty folder with --out, or a dataset folder to "
                                                 "continue with --resume)"};
    std::error_code ec;
    if (!fs::is_directory(dir, ec) || fs::is_empty(dir, ec)) return {};  // new or empty
    if (holds_dataset(dir))
        return resume ? check_resumed_shard(dir, shard) : check_no_dataset_in(dir);
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir, ec)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    std::string listed;
    for (std::size_t i = 0; i < names.size() && i < 5; ++i) listed += (i ? ", " : "") + names[i];
    if (names.size() > 5) listed += ", ... (" + std::to_string(names.size()) + " in all)";
    return {ErrorCode::invalid_argument,
            "--out " + dir.string() + " is not empty and holds no dataset (no manifest.csv or dataset-info.csv; it has " +
                listed + "): a run would write over its files" + (resume ? ", and --resume continues datasets only" : "") +
                "; choose a new or empty folder with --out"};
}

std::map<std::string, fs::file_time_type> folder_state(const fs::path& dir) {
    std::map<std::string, fs::file_time_type> state;
    std::error_code ec;
    if (!fs::exists(dir, ec)) return state;
    state[""] = fs::last_write_time(dir, ec);
    if (fs::is_directory(dir, ec))
        for (const auto& entry : fs::directory_iterator(dir, ec)) state[entry.path().filename().string()] = entry.last_write_time(ec);
    return state;
}

bool remove_empty_dataset(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return false;
    if (fs::exists(dir / "trials", ec) && !fs::is_empty(dir / "trials", ec)) return false;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const auto name = entry.path().filename().string();
        if (!is_dataset_file(name)) return false;
    }
    if (ec) return false;
    return fs::remove_all(dir, ec) > 0 && !ec;
}

}  // namespace rollsense::cli
