#include "cli/run_dataset.hpp"

#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

#include "rollsense/atomic_file.hpp"
#include "rollsense/checksum.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/dataset_files.hpp"
#include "rollsense/run_config.hpp"
#include "rollsense/shell_words.hpp"
#include "runtime/profile/profile.hpp"

namespace rollsense::cli {
namespace fs = std::filesystem;

namespace {
std::string file_text(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

std::string file_digest(const fs::path& file) {
    std::error_code ec;
    return fs::is_regular_file(file, ec) ? fnv1a_hex(file_text(file)) : "(unreadable)";
}

// The level of a long bracket (`[[` 1, `[==[` 3) opening at `at`, or 0 where none opens.
std::size_t long_bracket(const std::string& t, std::size_t at) {
    if (at >= t.size() || t[at] != '[') return 0;
    std::size_t e = at + 1;
    while (e < t.size() && t[e] == '=') ++e;
    return e < t.size() && t[e] == '[' ? e - at : 0;
}

// Lua source with its comments dropped and its strings kept, so that neither a call commented out is taken for one
// nor a `--` inside a string for a comment (diff reviews: a string holding "--[[" hid every later require).
std::string without_comments(const std::string& t) {
    const auto long_end = [&](std::size_t from, std::size_t level) {  // past the close of a long bracket, or the end
        const auto end = t.find("]" + std::string(level - 1, '=') + "]", from);
        return end == std::string::npos ? t.size() : end + level + 1;
    };
    std::string out;
    for (std::size_t i = 0; i < t.size();) {
        std::size_t next = i + 1;
        if (t.compare(i, 2, "--") == 0) {  // a comment: long, or to the end of its line
            const auto level = long_bracket(t, i + 2);
            next = level ? long_end(i + level + 3, level) : std::min(t.find('\n', i), t.size());
            out += ' ';
            i = next;
            continue;
        }
        if (const auto level = long_bracket(t, i)) {  // a long string
            next = long_end(i + level + 1, level);
        } else if (t[i] == '"' || t[i] == '\'') {  // a short string, its escapes skipped
            while (next < t.size() && t[next] != t[i] && t[next] != '\n') next += t[next] == '\\' ? 2 : 1;
            next = std::min(next + 1, t.size());
        }
        out.append(t, i, next - i);
        i = next;
    }
    return out;
}

// The files a script or a profile reads besides itself, found by their literal calls (`require "lib.helper"`,
// `pcall(require, "lib.helper")`, `include("etroll-joints")`), each once, depth first: a `KIND.NAME_fnv1a` row each,
// so that a resume refuses an edited module or included profile as it refuses an edited script (Lua review: a resume
// mixed the trials of two versions of a helper module). A name computed at run time is not seen; one not found is
// the run's own error.
void add_read_files(RunConfig& config, const fs::path& file, const std::string& call_name, const std::string& kind,
                    const std::function<std::optional<fs::path>(const std::string&)>& resolve) {
    // Not a method or field of that name (`x.require "m"`): a plain call, or pcall's argument.
    static const std::regex call(R"((^|[^\w.:])(require|include)\s*[(,]?\s*["']([A-Za-z0-9_./-]+)["'])");
    const std::string text = without_comments(file_text(file));
    for (std::sregex_iterator it(text.begin(), text.end(), call), end; it != end; ++it) {
        if ((*it)[2] != call_name) continue;
        const std::string name = (*it)[3], key = kind + "." + name + "_fnv1a";
        const auto found = resolve(name);
        if (!found || std::ranges::any_of(config, [&](const auto& row) { return row.first == key; })) continue;
        config.emplace_back(key, file_digest(*found));
        add_read_files(config, *found, call_name, kind, resolve);
    }
}
}  // namespace

RunConfig run_config_of(const fs::path& script, const std::string& profile, const fs::path& profile_file,
                        const fs::path& share_dir, std::uint64_t seed, const SetOptions& sets) {
    RunConfig config{{"rollsense_version", ROLLSENSE_VERSION_STRING},
                     {"script", script.filename().string()},
                     {"script_fnv1a", file_digest(script)}};
    // Where the sandbox looks for a module (beside the script, then share/lua), and the profile loader for an include.
    const fs::path script_dir = script.parent_path().empty() ? fs::path(".") : script.parent_path();
    add_read_files(config, script, "require", "module", [&](const std::string& name) -> std::optional<fs::path> {
        std::string rel = name;
        std::ranges::replace(rel, '.', '/');
        std::error_code ec;
        for (const auto& dir : {script_dir, share_dir / "lua"})
            if (fs::is_regular_file(dir / (rel + ".lua"), ec)) return dir / (rel + ".lua");
        return std::nullopt;
    });
    config.emplace_back("profile", profile);
    config.emplace_back("profile_fnv1a", file_digest(profile_file));
    add_read_files(config, profile_file, "include", "include", [&](const std::string& name) -> std::optional<fs::path> {
        std::error_code ec;
        const auto path = runtime::resolve_profile_path(name, share_dir);
        return fs::is_regular_file(path, ec) ? std::optional(path) : std::nullopt;
    });
    config.emplace_back("seed", std::to_string(seed));
    std::map<std::string, std::string> last;
    for (const auto& [key, value] : sets) last[key] = value;
    for (const auto& [key, value] : last) config.emplace_back("set." + key, value);
    return config;
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
    if (fs::exists(dir / kRunInfoFile, ec)) {
        auto info = csv::read_key_values(dir / kRunInfoFile);
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
    // Review: a whole run killed before its end was resumed as a shard, mixing the two.
    if (!recorded && run_killed_before_end(dir)) recorded = "";
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
                              (dir / (*recorded == "K/N" ? kShardPlanFile : kRunInfoFile)).string() + ")";
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
    // User review: a resume into a misspelt folder recorded the whole run again there, the stopped dataset left as it was.
    if (resume && !fs::exists(dir, ec))
        return {ErrorCode::invalid_argument,
                "--resume: " + dir.string() + " does not exist: there is no dataset to continue there (the stopped "
                "run printed its folder after \"continue with:\"); check the path, or start a new dataset there without "
                "--resume"};
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
