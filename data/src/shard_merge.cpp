#include "rollsense/shard_merge.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>

#include <map>
#include <optional>
#include <unordered_map>

#include "rollsense/atomic_file.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/directory_lock.hpp"
#include "rollsense/run_config.hpp"
#include "rollsense/shard.hpp"
#include "rollsense/shell_words.hpp"

namespace rollsense {
namespace fs = std::filesystem;

namespace {

// Problems listed in one refusal before the rest are only counted.
constexpr std::size_t kProblemsShown = 10;
// Trial files written per group commit.
constexpr std::size_t kFilesPerCommit = 256;

using csv::KeyValues;

// The value of the last row named `key`, or nullptr.
const std::string* find_value(const KeyValues& entries, std::string_view key) {
    for (auto it = entries.rbegin(); it != entries.rend(); ++it)
        if (it->first == key) return &it->second;
    return nullptr;
}

struct ShardDataset {
    fs::path dir;
    DirectoryLock lock;  // shared: no run writes into it while it is read, other merges may read it
    Shard shard;
    KeyValues run_info;
    std::vector<std::string> plan;
    DatasetReader dataset;

    std::string label() const { return dir.string() + " (shard " + shard.text() + ")"; }
    std::string value(std::string_view key) const {
        const std::string* v = find_value(run_info, key);
        return v ? *v : std::string();
    }
};

Error refused(const std::string& message) { return Error{ErrorCode::invalid_argument, message}; }

// `e`, about a file of the shard in `dir`, with the way out: the shard's run
// resumed writes its plan again and records a trial that does not load again.
Error with_repair(Error e, const fs::path& dir) {
    e.message += "; repair the shard by resuming it, '" + resume_command(dir) +
                 "' with the script and options of its run-info.csv, then merge again";
    return e;
}

Result<ShardDataset> open_shard(const fs::path& dir) {
    ShardDataset s;
    s.dir = dir;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return Error{ErrorCode::not_found, dir.string() + ": no such shard folder"};
    auto lock = DirectoryLock::acquire_to_read(dir);
    if (!lock) return lock.error();
    s.lock = std::move(lock).value();
    const fs::path run_info = dir / kRunInfoFile;
    // Review: a whole run killed before its end was told to resume and merge, and the merge then refused it as a
    // whole run.
    if (run_killed_before_end(dir))
        return refused(dir.string() + " has run-config.csv but no run-info.csv: its run was killed before its end, and "
                       "was a whole run, not a shard (a shard's run writes run-info.csv as it starts, naming its "
                       "shard); resume it without --shard to complete it. A shard killed in its first instant looks "
                       "the same: resume it with its --shard K/N and the same --out, then merge");
    if (!fs::exists(run_info, ec))
        return refused(run_info.string() + " is missing: " + dir.string() + " is not the folder of a run " +
                       "(a shard's run writes it as it starts); give the folders 'rollsense run SCRIPT --shard K/N "
                       "--out SHARD' recorded");
    auto info = csv::read_key_values(run_info);
    if (!info) return info.error();
    s.run_info = std::move(info).value();
    const std::string* shard = find_value(s.run_info, "shard");
    if (!shard)
        return refused(run_info.string() + ": no 'shard' row: " + dir.string() +
                       " was recorded without --shard K/N, so it is a whole run, not a shard of one");
    auto parsed = parse_shard(*shard, run_info.string() + ": shard");
    if (!parsed) return parsed.error();
    s.shard = *parsed;
    if (const auto status = s.value("status"); status != "ok")
        return refused(s.label() + " did not finish: its run-info.csv says status '" + status +
                       "'; finish it with the command line in that file plus --resume, then merge");
    auto plan = read_shard_plan(dir, s.shard.count);
    if (!plan) return with_repair(plan.error(), dir);
    s.plan = std::move(plan).value();
    auto dataset = DatasetReader::open(dir);
    if (!dataset) return dataset.error();
    s.dataset = std::move(dataset).value();
    return s;
}

// The --set KEY=VALUE options of a command line as run-info.csv records it
// (words quoted for the shell), the last value of each key.
std::map<std::string, std::string> set_options(const std::string& command_line) {
    const std::vector<std::string> words = shell_split(command_line);
    std::map<std::string, std::string> out;
    for (std::size_t i = 0; i < words.size(); ++i) {
        std::string kv;
        if (words[i] == "--set" && i + 1 < words.size())
            kv = words[++i];
        else if (words[i].rfind("--set=", 0) == 0)
            kv = words[i].substr(6);
        else
            continue;
        const auto eq = kv.find('=');
        out[kv.substr(0, eq)] = eq == std::string::npos ? "" : kv.substr(eq + 1);
    }
    return out;
}

// What decides the trials a shard records, as "file key" → value.
Result<KeyValues> configuration(const ShardDataset& s) {
    KeyValues out;
    auto add_file = [&](const char* name) -> Status {
        auto rows = csv::read_key_values(s.dir / name);
        if (!rows) return rows.error();
        for (auto& [k, v] : *rows) out.emplace_back(std::string(name) + " " + k, v);
        return {};
    };
    if (auto st = add_file("dataset-info.csv"); !st) return st.error();
    // The run configuration --resume checks (script and profile with their
    // digests, seed, every --set): when the shards have it, it says it all.
    std::error_code ec;
    if (fs::exists(s.dir / kRunConfigFile, ec)) {
        if (auto st = add_file(kRunConfigFile); !st) return st.error();
        return out;
    }
    for (const char* key : {"script", "profile", "seed"}) out.emplace_back(std::string("run-info.csv ") + key, s.value(key));
    for (const auto& [k, v] : set_options(s.value("command_line")))
        out.emplace_back("run-info.csv command line --set " + k, v);
    return out;
}

// "what: A here, B there" for every entry that differs.
std::vector<std::string> differences(const KeyValues& here, const KeyValues& there) {
    std::map<std::string, std::pair<std::optional<std::string>, std::optional<std::string>>> both;
    for (const auto& [k, v] : here) both[k].first = v;
    for (const auto& [k, v] : there) both[k].second = v;
    std::vector<std::string> out;
    const auto shown = [](const std::optional<std::string>& v) { return v ? "'" + *v + "'" : std::string("(none)"); };
    // A shard whose run-config.csv lists no module or included profile was recorded before it listed them: those
    // rows are not compared with it (diff reviews; --resume is as lenient: run_config_differences).
    const std::string prefix = std::string(kRunConfigFile) + " ";  // configuration(): "FILE KEY"
    const auto read_file = [&](const std::string& k) {
        return k.starts_with(prefix) && is_read_file_key(std::string_view(k).substr(prefix.size()));
    };
    const auto lists = [&](const KeyValues& config) {
        return std::ranges::any_of(config, [&](const auto& row) { return read_file(row.first); });
    };
    const bool both_list = lists(here) && lists(there);
    for (const auto& [k, v] : both)
        if (v.first != v.second && (both_list || !read_file(k)))
            out.push_back(k + ": " + shown(v.first) + " vs " + shown(v.second));
    return out;
}

std::string listed(const std::vector<std::string>& problems, const std::string& separator) {
    std::string out;
    for (std::size_t i = 0; i < problems.size() && i < kProblemsShown; ++i) out += (i ? separator : "") + problems[i];
    if (problems.size() > kProblemsShown)
        out += separator + "... and " + std::to_string(problems.size() - kProblemsShown) + " more";
    return out;
}

// Shards 0..N-1 of one N, each once; returns them ordered by K.
Result<std::vector<ShardDataset>> order_shards(std::vector<ShardDataset> shards) {
    const std::size_t n = shards.front().shard.count;
    const std::string first = shards.front().label();  // before it is moved into place
    std::vector<std::optional<ShardDataset>> by_k(n);
    for (auto& s : shards) {
        if (s.shard.count != n)
            return refused(s.label() + " and " + first +
                           " come from different splits of a run (N = " + std::to_string(s.shard.count) + " and " +
                           std::to_string(n) + "); merge the N shards of one run");
        auto& slot = by_k[s.shard.index];
        if (slot) return refused(slot->dir.string() + " and " + s.dir.string() + " are both shard " + s.shard.text());
        slot = std::move(s);
    }
    std::vector<std::string> missing;
    for (std::size_t k = 0; k < n; ++k)
        if (!by_k[k]) missing.push_back(Shard{k, n}.text());
    if (!missing.empty())
        return refused("shard " + listed(missing, ", ") + " missing: give the folders of all " + std::to_string(n) +
                       " shards of the run (" + std::to_string(shards.size()) + " given)");
    std::vector<ShardDataset> out;
    for (auto& s : by_k) out.push_back(std::move(*s));
    return out;
}

Status check_same_run(const std::vector<ShardDataset>& shards) {
    const ShardDataset& first = shards.front();
    auto reference = configuration(first);
    if (!reference) return reference.error();
    for (std::size_t k = 1; k < shards.size(); ++k) {
        const ShardDataset& s = shards[k];
        auto config = configuration(s);
        if (!config) return config.error();
        if (auto d = differences(*config, *reference); !d.empty())
            return refused(s.label() + " was recorded with another configuration than " + first.label() + ": " +
                           listed(d, "; ") + " (this shard's value first); the shards of a run are recorded with one "
                           "script, profile, seed and settings: record this shard again with the others' command line");
        if (s.plan != first.plan) {
            std::size_t i = 0;
            while (i < s.plan.size() && i < first.plan.size() && s.plan[i] == first.plan[i]) ++i;
            const auto at = [i](const std::vector<std::string>& plan) {
                return i < plan.size() ? "'" + plan[i] + "'" : std::string("the end of its plan");
            };
            return refused(s.label() + " planned other trials than " + first.label() + " (shard-plan.csv): trial " +
                           std::to_string(i) + " of the run is " + at(s.plan) + " in the one, " + at(first.plan) +
                           " in the other; the script or its settings changed between the shards, or the script's "
                           "order of trials is not reproducible (e.g. it follows pairs() over a table, whose order "
                           "changes from process to process: walk a list with ipairs, or sort the keys)");
        }
    }
    return {};
}

struct ManifestRows {
    std::vector<std::string> header;
    std::unordered_map<std::string, std::vector<std::string>> by_id;
};

// manifest.csv as it is written, row by row, so the merged one is byte for
// byte what the run wrote, whatever columns it has.
Result<ManifestRows> read_manifest_rows(const fs::path& dir) {
    auto reader = csv::Reader::open(dir / "manifest.csv");
    if (!reader) return reader.error();
    auto id = reader->column("trial_id");
    if (!id) return id.error();
    ManifestRows rows;
    rows.header = reader->header();
    std::vector<std::string> f;
    for (;;) {
        auto more = reader->next(f);
        if (!more) return more.error();
        if (!*more) break;
        rows.by_id[f[*id]] = f;
    }
    return rows;
}

struct Placed {
    const ShardDataset* shard = nullptr;
    const TrialRecord* record = nullptr;
};

// Every planned trial exactly once, in the shard the plan gives it to.
Result<std::vector<Placed>> place_trials(const std::vector<ShardDataset>& shards) {
    const auto& plan = shards.front().plan;
    const Shard split = shards.front().shard;
    std::unordered_map<std::string, std::size_t> index_of;
    for (std::size_t i = 0; i < plan.size(); ++i) index_of.emplace(plan[i], i);
    std::vector<Placed> placed(plan.size());
    std::vector<std::string> problems;
    for (const auto& s : shards) {
        for (const auto& r : s.dataset.trials()) {
            const auto it = index_of.find(r.info.id);
            if (it == index_of.end()) {
                problems.push_back(s.label() + " holds trial '" + r.info.id + "', which the run's plan does not list");
                continue;
            }
            const std::size_t owner = split.owner(it->second);
            auto& p = placed[it->second];
            if (p.shard) {
                problems.push_back("trial '" + r.info.id + "' is duplicated: " + p.shard->label() + " and " + s.label() +
                                   " both hold it (the plan gives it to shard " + Shard{owner, split.count}.text() + ")");
                continue;
            }
            if (owner != s.shard.index)
                problems.push_back(s.label() + " holds trial '" + r.info.id + "', which the plan gives to shard " +
                                   Shard{owner, split.count}.text());
            p = {&s, &r};
        }
    }
    for (std::size_t i = 0; i < plan.size(); ++i)
        if (!placed[i].shard)
            problems.push_back("trial '" + plan[i] + "' (trial " + std::to_string(i) + " of the run) is missing from " +
                               shards[split.owner(i)].label() + "; record it with '" +
                               resume_command(shards[split.owner(i)].dir) +
                               "' with the script and options of its run-info.csv");
    if (!problems.empty()) return refused(std::to_string(problems.size()) + " problem(s) with the shards' trials: " + listed(problems, "; "));
    return placed;
}

std::string shards_csv(const std::vector<ShardDataset>& shards) {
    std::string out;
    csv::append_row(out, {"shard", "folder", "trials", "date_utc", "wall_time_s", "command_line"});
    for (const auto& s : shards) {
        std::error_code ec;
        const fs::path folder = fs::absolute(s.dir, ec).lexically_normal();
        csv::append_row(out, {s.shard.text(), (ec ? s.dir : folder).string(), std::to_string(s.dataset.trials().size()),
                              s.value("date_utc"), s.value("wall_time_s"), s.value("command_line")});
    }
    return out;
}

// OUT with its symbolic links followed: a link's folder takes the merge and the
// link stays (the final rename could only replace the link itself, and a link
// cannot be replaced by a folder). A link to nothing names the folder to create.
Result<fs::path> followed(fs::path out) {
    for (int links = 0; links < 40; ++links) {  // as many as the kernel follows in a path (ELOOP)
        std::error_code ec;
        if (!fs::is_symlink(out, ec)) return out;
        const fs::path target = fs::read_symlink(out, ec);
        if (ec) return Error{ErrorCode::io_error, out.string() + ": cannot read the link: " + ec.message()};
        out = target.is_absolute() ? target : out.parent_path() / target;
        if (!out.has_filename()) out = out.parent_path();  // a link to "dir/"
    }
    return refused(out.string() + ": too many levels of symbolic links: merge into a folder");
}

Status check_out_folder(const fs::path& out) {
    if (auto s = check_can_be_folder(out); !s) return refused(s.message() + ": merge into a new folder");
    std::error_code ec;
    if (!fs::exists(out, ec)) return {};
    if (!fs::is_directory(out, ec) || !fs::is_empty(out, ec))
        return refused(out.string() + " already exists and is not empty: merge into a new folder");
    return {};
}

// The merged trials/, manifest.csv, dataset-info.csv, run-config.csv and
// shards.csv, written into `dir`.
Status write_merged(const fs::path& dir, const std::vector<ShardDataset>& shards, const std::vector<Placed>& placed,
                    const std::vector<ManifestRows>& manifests) {
    std::error_code ec;
    fs::create_directories(dir / "trials", ec);
    if (ec) return {ErrorCode::io_error, (dir / "trials").string() + ": cannot create: " + ec.message()};
    // The trial files first, each checked as a reader loads it; the manifest
    // that lists them last.
    std::string manifest;
    csv::append_row(manifest, manifests.front().header);
    std::vector<PendingFile> batch;
    for (const auto& p : placed) {
        if (auto data = p.shard->dataset.load(*p.record); !data) return with_repair(data.error(), p.shard->dir);
        auto bytes = csv::read_file(p.shard->dir / p.record->file);
        if (!bytes) return bytes.error();
        batch.push_back({dir / p.record->file, std::move(bytes).value()});
        if (batch.size() >= kFilesPerCommit) {
            if (auto s = write_files_atomic(batch); !s) return s;
            batch.clear();
        }
        const auto k = static_cast<std::size_t>(p.shard - shards.data());
        csv::append_row(manifest, manifests[k].by_id.at(p.record->info.id));
    }
    for (const char* name : {"dataset-info.csv", kRunConfigFile}) {
        if (!fs::exists(shards.front().dir / name, ec)) continue;
        auto bytes = csv::read_file(shards.front().dir / name);
        if (!bytes) return bytes.error();
        batch.push_back({dir / name, std::move(bytes).value()});
    }
    batch.push_back({dir / kShardsFile, shards_csv(shards)});
    if (auto s = write_files_atomic(batch); !s) return s;
    return write_file_atomic(dir / "manifest.csv", manifest);
}

// The staging folders of earlier merges into `out` whose process is gone
// (Ctrl-C, kill -9, a node lost): removed, so that none stays for good. A
// merge still running keeps its own.
void remove_dead_stagings(const fs::path& out, const std::string& prefix) {
    std::error_code ec;
    const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    for (const auto& e : fs::directory_iterator(parent, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const char* first = name.data() + prefix.size();
        const char* last = name.data() + name.size();
        pid_t pid = 0;
        const auto [end, err] = std::from_chars(first, last, pid);
        if (err == std::errc() && end == last && pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH)
            fs::remove_all(e.path(), ec);
    }
}

// `e` with every mention of the sibling folder `staged` turned into `out`.
Error as_written_to(Error e, const fs::path& staged, const fs::path& out) {
    const std::string from = staged.string(), to = out.string();
    for (auto at = e.message.find(from); at != std::string::npos; at = e.message.find(from, at + to.size()))
        e.message.replace(at, from.size(), to);
    return e;
}

// OUT with its links followed, once it is checked; and each shard folder given once.
Result<fs::path> checked_arguments(const fs::path& out_given, const std::vector<fs::path>& dirs) {
    if (dirs.empty()) return refused("no shard folders given");
    // "OUT/" names OUT: its sibling is named after the last part that is not empty.
    auto resolved = followed(out_given.has_filename() ? out_given : out_given.parent_path());
    if (!resolved) return resolved.error();
    if (auto s = check_out_folder(*resolved); !s) return s.error();
    std::map<fs::path, fs::path> given;  // each folder once (it is locked while read)
    for (const auto& dir : dirs) {
        std::error_code ec;
        const auto canonical = fs::weakly_canonical(dir, ec);
        if (auto [it, added] = given.emplace(ec ? dir : canonical, dir); !added)
            return refused(dir.string() + " is given twice (also as " + it->second.string() +
                           "): give each shard's folder once");
    }
    return resolved;
}

}  // namespace

Status check_merge_arguments(const fs::path& out, const std::vector<fs::path>& shards) {
    auto checked = checked_arguments(out, shards);
    if (!checked) return checked.error();
    return {};
}

Result<MergeSummary> merge_shards(const fs::path& out_given, const std::vector<fs::path>& dirs,
                                  const MergeFinish& finish) {
    const auto resolved = checked_arguments(out_given, dirs);
    if (!resolved) return resolved.error();
    const fs::path& out = *resolved;
    std::vector<ShardDataset> opened;
    for (const auto& dir : dirs) {
        auto s = open_shard(dir);
        if (!s) return s.error();
        opened.push_back(std::move(s).value());
    }
    auto ordered = order_shards(std::move(opened));
    if (!ordered) return ordered.error();
    const std::vector<ShardDataset>& shards = *ordered;
    if (auto s = check_same_run(shards); !s) return s.error();
    auto placed = place_trials(shards);
    if (!placed) return placed.error();

    std::vector<ManifestRows> manifests;
    for (const auto& s : shards) {
        auto rows = read_manifest_rows(s.dir);
        if (!rows) return rows.error();
        if (!manifests.empty() && rows->header != manifests.front().header)
            return refused(s.label() + ": manifest.csv has other columns than " + shards.front().label() +
                           "'s (recorded by another rollsense version?)");
        manifests.push_back(std::move(rows).value());
    }

    // Written beside OUT and renamed to it at the end: nothing is left behind
    // on failure but the missing parents of OUT this created, removed too.
    const std::string staging_prefix = "." + out.filename().string() + ".tmp-";
    const fs::path staged = out.parent_path() / (staging_prefix + std::to_string(::getpid()));
    fs::path created = staged;  // the outermost folder this merge creates
    std::error_code ec;
    for (auto p = out.parent_path(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) created = p;
    const MergeSummary summary{shards.size(), placed->size(), shards.front().value("command_line"),
                               shards.front().value("working_dir")};
    remove_dead_stagings(out, staging_prefix);
    fs::remove_all(staged, ec);  // a killed merge's, whose process id this one reuses
    // The staging folder on its own first: a folder this user cannot write in
    // (permissions, a read-only file system) is named with the way out, not
    // reported as OUT/trials that cannot be created.
    if (fs::create_directories(staged, ec); ec) {
        auto where = staged.parent_path();
        std::error_code gone;
        while (!where.empty() && !fs::exists(where, gone)) where = where.parent_path();
        const std::string folder = where.empty() ? std::string(".") : where.string();
        fs::remove_all(created, gone);
        // "Make it writable" only where permissions are the cause (diff review: said of a full disk and of /proc).
        const bool permissions = ec == std::errc::permission_denied || ec == std::errc::operation_not_permitted ||
                                 ec == std::errc::read_only_file_system;
        return Error{ErrorCode::io_error, "cannot merge into " + out.string() + ": " + folder +
                                              " cannot be written (" + ec.message() + "); choose another OUT" +
                                              (permissions ? ", or make " + folder + " writable for this user" : "")};
    }
    Status st = write_merged(staged, shards, *placed, manifests);
    if (st && finish) st = finish(staged, summary);
    // An empty OUT that the merge replaces keeps its permissions (its owner only
    // root could keep: the merged folder is the merging user's).
    if (const auto kept = fs::status(out, ec).permissions(); st && fs::is_directory(out, ec)) {
        fs::permissions(staged, kept, ec);
        if (ec) st = {ErrorCode::io_error, out.string() + ": cannot keep its permissions: " + ec.message()};
    }
    if (st) st = rename_durable(staged, out);
    if (!st) {
        fs::remove_all(created, ec);
        return as_written_to(st.error(), staged, out);
    }
    return summary;
}

}  // namespace rollsense
