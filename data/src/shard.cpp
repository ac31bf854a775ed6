#include "rollsense/shard.hpp"

#include "rollsense/csv.hpp"
#include "rollsense/run_config.hpp"
#include "rollsense/shell_words.hpp"

namespace rollsense {

Result<Shard> parse_shard(std::string_view text, std::string_view what) {
    const std::string expected = std::string(what) + " expects K/N, this process's shard K of N, with whole numbers 0 <= K < N and 2 <= N <= " +
                                 std::to_string(kMaxShards) + " (e.g. 0/4 ... 3/4), got '" + std::string(text) + "'";
    const auto slash = text.find('/');
    if (slash == std::string_view::npos) return Error{ErrorCode::invalid_argument, expected};
    auto k = csv::parse_unsigned(text.substr(0, slash), kMaxShards, std::string(what) + " K");
    auto n = csv::parse_unsigned(text.substr(slash + 1), kMaxShards, std::string(what) + " N");
    if (!k || !n || *n == 0) return Error{ErrorCode::invalid_argument, expected};
    // One shard would be the whole run, yet analyse and merge as a part: refused
    // rather than given a meaning of its own (rs.shard() says 0, 1 unsharded).
    if (*n == 1)
        return Error{ErrorCode::invalid_argument, std::string(what) + " " + std::string(text) +
                                                      ": --shard K/N needs N >= 2; run without --shard for one process"};
    if (*k >= *n)
        return Error{ErrorCode::invalid_argument, std::string(what) + " " + std::string(text) + ": shard K = " +
                                                      std::to_string(*k) + " is not below N = " + std::to_string(*n) +
                                                      " (the shards of a run split " + std::to_string(*n) +
                                                      " ways are 0/" + std::to_string(*n) + " ... " +
                                                      std::to_string(*n - 1) + "/" + std::to_string(*n) + ")"};
    return Shard{static_cast<std::size_t>(*k), static_cast<std::size_t>(*n)};
}

bool ShardPlan::claim(const std::string& trial_id) {
    auto [it, added] = index_.try_emplace(trial_id, order_.size());
    if (added) order_.push_back(trial_id);
    return shard_.owner(it->second) == shard_.index;
}

Status ShardPlan::check_save(const std::string& trial_id) const {
    const auto it = index_.find(trial_id);
    if (it == index_.end())
        return {ErrorCode::state_error,
                "trial '" + trial_id + "' cannot be saved by shard " + shard_.text() +
                    ": the script did not ask rs.has_trial('" + trial_id + "') first, and a shard learns which " +
                    "trials are its own from that question; record trials as `if not rs.has_trial(id) then ... end` " +
                    "(docs/cluster.md)"};
    const std::size_t owner = shard_.owner(it->second);
    if (owner != shard_.index)
        return {ErrorCode::state_error,
                "trial '" + trial_id + "' (trial " + std::to_string(it->second) + " of the run) belongs to shard " +
                    Shard{owner, shard_.count}.text() + ", not to this shard " + shard_.text() +
                    "; skip it when rs.has_trial(id) returns true (docs/cluster.md)"};
    return {};
}

std::string ShardPlan::csv() const {
    std::string out;
    csv::append_row(out, {"trial_id", "shard"});
    for (std::size_t i = 0; i < order_.size(); ++i) csv::append_row(out, {order_[i], std::to_string(shard_.owner(i))});
    return out;
}

std::string resume_command(const std::filesystem::path& dir) {
    std::string shard;
    if (auto info = csv::read_key_values(dir / kRunInfoFile))
        for (const auto& [key, value] : *info)
            if (key == "shard") shard = " --shard " + value;
    return "rollsense run SCRIPT" + shard + " --out " + shell_quote(dir.string()) + " --resume";
}

Result<std::vector<std::string>> read_shard_plan(const std::filesystem::path& dir, std::size_t count) {
    auto reader = csv::Reader::open(dir / kShardPlanFile);
    if (!reader) return reader.error();
    auto id_col = reader->column("trial_id");
    if (!id_col) return id_col.error();
    auto shard_col = reader->column("shard");
    if (!shard_col) return shard_col.error();
    std::vector<std::string> out;
    std::unordered_map<std::string, std::size_t> line_of;
    std::vector<std::string> f;
    for (;;) {
        auto more = reader->next(f);
        if (!more) return more.error();
        if (!*more) break;
        auto shard = reader->unsigned_integer(f, *shard_col, kMaxShards);
        if (!shard) return shard.error();
        const std::size_t expected = out.size() % count;
        if (*shard != expected)
            return Error{ErrorCode::parse_error, reader->where(*shard_col) + ": trial " + std::to_string(out.size()) +
                                                     " of a run split " + std::to_string(count) + " ways belongs to shard " +
                                                     std::to_string(expected) + ", the file says " + f[*shard_col]};
        const std::string& id = f[*id_col];
        if (auto [it, added] = line_of.try_emplace(id, reader->line()); !added)
            return Error{ErrorCode::parse_error, reader->where(*id_col) + ": trial '" + id +
                                                     "' is planned twice (first on line " + std::to_string(it->second) +
                                                     ")"};
        out.push_back(id);
    }
    return out;
}

}  // namespace rollsense
