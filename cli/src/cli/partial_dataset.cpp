#include "cli/partial_dataset.hpp"

#include <algorithm>
#include <string>

#include "rollsense/csv.hpp"
#include "rollsense/directory_lock.hpp"
#include "rollsense/log.hpp"
#include "rollsense/run_config.hpp"

namespace rollsense::cli {

// Review (sharded runs): features, evaluate, train and report took a shard, a killed run and a folder being
// recorded without a word, while merge and rs.analyse refuse them. They may be what the user means to look at (a
// first look at a long run), so they are analysed, with a warning that says what is missing and the way to all of it.
void warn_if_partial(const std::filesystem::path& dataset) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dataset, ec)) return;
    const std::string dir = dataset.string();
    if (auto lock = DirectoryLock::acquire_to_read(dataset); !lock && lock.error().code == ErrorCode::state_error) {
        log_warning("rollsense", dir + " is being recorded by a run now: only the trials saved so far are read (analyse "
                                   "it again once the run has ended)");
        return;
    }
    if (run_killed_before_end(dataset)) {
        log_warning("rollsense", "the run that recorded " + dir + " did not end (no run-info.csv: killed, or its "
                                 "machine stopped), so it may hold only part of its trials: resume it to complete them "
                                 "(its command with --resume)");
        return;
    }
    auto info = csv::read_key_values(dataset / kRunInfoFile);
    if (!info) return;  // recorded before run-info.csv, or unreadable: the readers say what they need
    std::string shard, status;
    for (const auto& [key, value] : *info) {
        if (key == "shard") shard = value;
        if (key == "status") status = value;
    }
    if (!shard.empty())
        log_warning("rollsense", dir + " is shard " + shard + " of a run and holds only its part of the trials: merge the "
                                   "shards first for the whole run (rollsense merge OUT SHARD..., docs/cluster.md)");
    else if (!status.empty() && status != "ok") {
        // Its first line, bounded (a script's error may carry a traceback); the run may have failed after its last
        // trial (its analysis, its cleanup), so what is missing is not known here (diff review).
        std::string said = status.substr(0, std::min<std::size_t>(status.find('\n'), 160));
        if (said.size() < status.size()) said += " ...";
        log_warning("rollsense", "the run that recorded " + dir + " did not end ok (run-info.csv: status '" + said +
                                 "'): if it stopped before its last trial it holds only part of them; resume it to "
                                 "complete them (its command_line in run-info.csv with --resume)");
    }
}

}  // namespace rollsense::cli
