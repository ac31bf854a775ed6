// rollsense merge OUT SHARD...: the datasets of a sharded run joined into the
// dataset the unsharded run records, with its features.
#include <cstdio>
#include <string>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "rollsense/atomic_file.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/features.hpp"
#include "rollsense/run_config.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/shard_merge.hpp"
#include "rollsense/shell_words.hpp"
#include "analysis/report/provenance.hpp"

namespace rollsense::cli {
namespace {

const char* kHelp = R"(usage: rollsense merge OUT SHARD... [options]

Join the datasets of the N shards of one run (rollsense run SCRIPT --shard K/N
--out SHARD, one process per shard: docs/cluster.md) into OUT, the dataset the
unsharded run records with the same seed: trials/, manifest.csv (the trials in
the run's order), dataset-info.csv (and run-config.csv when the shards have
one) byte for byte, and features.csv with the paper's feature settings, as the
stock script's analysis writes it. OUT also gets shards.csv (one row per
shard: its folder, trials, date, wall time, command line) and run-info.csv
(this merge). OUT must be new or empty, and each SHARD folder given once
(else a usage error, exit 2, with nothing written); the merge is written
into a hidden sibling, .OUT.tmp-PID, renamed to OUT once complete (an empty OUT keeps its
permissions), so OUT's folder must be writable: else the merge stops naming
it and the reason (exit 5). An OUT that is a symbolic link is merged into the folder the
link names (which may be new), and the link stays.

Refused, with nothing written (and so is a merge that fails), unless the SHARD folders are exactly the shards
0/N ... N-1/N of one run: each finished (status ok), recorded with the same
profile, seed, script and settings and the same plan of trials
(shard-plan.csv), holding between them every trial of the run once. The error
names the shard folder and the difference (exit 3).

Then analyse OUT as the unsharded run does: the shards' command line without
--shard, with --out OUT --resume (every trial is found on disk, so the script
goes straight to its analysis; printed at the end), or 'rollsense report OUT'.

options:
  --threads N           feature extraction threads (0 = all cores; results do
                        not depend on it)
  -v, --verbose         debug messages;   -q, --quiet   no info messages: warnings, errors
                        and the closing summary (what was merged, the way on))";

// The shards' command line turned into the one that analyses the merged dataset: without --shard, --out and
// --resume, then --out OUT --resume; run from the folder the shards ran in when that is not this one, as their
// relative paths (the script, a profile file) start there (review: printed unquoted, and from here).
std::string analyse_command(const MergeSummary& merged, const std::filesystem::path& out) {
    std::vector<std::string> words;
    const auto shard_words = shell_split(merged.command_line);
    for (std::size_t i = 0; i < shard_words.size(); ++i) {
        const auto& w = shard_words[i];
        if (w == "--shard" || w == "--out") ++i;  // and its value
        else if (w != "--resume" && !w.starts_with("--shard=") && !w.starts_with("--out=")) words.push_back(w);
    }
    std::error_code ec;
    const bool elsewhere = !merged.working_dir.empty() && !std::filesystem::equivalent(merged.working_dir, ".", ec);
    words.insert(words.end(), {"--out", elsewhere ? std::filesystem::absolute(out, ec).string() : out.string(), "--resume"});
    return (elsewhere ? "cd " + shell_quote(merged.working_dir) + " && " : "") + shell_join(words);
}

int fail(const Error& e, int fallback) {
    std::fprintf(stderr, "rollsense merge: %s\n", e.message.c_str());
    return exit_code_for(e.code, fallback);
}

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    args.reject_unknown({"--threads", "-v", "--verbose", "-q", "--quiet"});
    const auto pos = args.positionals({"--threads"});
    if (pos.size() < 2) throw UsageError("expects OUT and at least one SHARD folder (see --help)");
    if (pos[0].empty()) throw UsageError("OUT is empty (''): give the folder to merge into");
    for (std::size_t i = 1; i < pos.size(); ++i)
        if (pos[i].empty()) throw UsageError("SHARD " + std::to_string(i) + " is empty (''): give each shard's folder");
    setup_logging(args);
    const auto threads = static_cast<unsigned>(args.unsigned_option("--threads", 0, 0, 4096));
    const std::filesystem::path out = pos[0];
    const std::vector<std::filesystem::path> shards(pos.begin() + 1, pos.end());

    // The command line's own mistakes (OUT not empty or a file, a shard given twice) exit 2 as `run --out` into a
    // folder that is not empty does; what is wrong in the shards themselves is the merge's to say (3).
    if (auto st = check_merge_arguments(out, shards); !st) {
        if (st.code() == ErrorCode::invalid_argument) throw UsageError(st.message());
        return fail(st.error(), kExitConfig);
    }

    const std::string command_line = "rollsense merge " + shell_join(argv);
    // features.csv and run-info.csv join the merged folder before it takes OUT's
    // name: a failure here leaves nothing behind either.
    const auto finish = [&](const std::filesystem::path& merged, const MergeSummary& summary) -> Status {
        auto dataset = DatasetReader::open(merged);
        if (!dataset) return dataset.error();
        auto rows = features::extract_dataset(*dataset, features::FeatureSettings{}, threads);
        if (!rows) return rows.error();
        if (auto s = features::write_features_csv(merged / "features.csv", *rows); !s) return s;
        const csv::KeyValues run_info{{"date_utc", report::utc_timestamp()},
                                      {"command_line", command_line},
                                      {"rollsense_version", ROLLSENSE_VERSION_STRING},
                                      {"status", "ok"},
                                      {"shards", std::to_string(summary.shards)},
                                      {"trials", std::to_string(summary.trials)}};
        return write_file_atomic(merged / kRunInfoFile, csv::format_key_values(run_info));
    };
    auto merged = merge_shards(out, shards, finish);
    if (!merged) return fail(merged.error(), kExitConfig);
    // The script's own analysis, or the stock one (a script run with its analysis off has none to resume).
    std::printf("merged %zu shards: %zu trials into %s (with features.csv)\nanalyse it as the unsharded run: %s\n"
                "or with the stock analysis: rollsense report %s\n",
                merged->shards, merged->trials, out.c_str(), analyse_command(*merged, out).c_str(),
                shell_quote(out.string()).c_str());
    return kExitOk;
}

const Registration reg{{"merge", "join the datasets of a sharded run (--shard K/N) into the whole run's dataset",
                        kHelp, &run}};

}  // namespace
}  // namespace rollsense::cli
