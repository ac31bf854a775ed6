// rollsense run SCRIPT: run a roll procedure on a robot profile.
#include <algorithm>
#include <cstdio>
#include <system_error>
#include <ctime>
#include <string>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "cli/paths.hpp"
#include "cli/progress_bar.hpp"
#include "cli/recorded_seed.hpp"
#include "cli/run_check.hpp"
#include "cli/run_dataset.hpp"
#include "live/live_view.hpp"
#include "analysis/lua/script_settings.hpp"
#include "analysis/lua/unfinished_analysis.hpp"
#include "rollsense/directory_lock.hpp"
#include "rollsense/hal/gpio.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/log.hpp"
#include "rollsense/run_config.hpp"
#include "rollsense/shard.hpp"
#include "rollsense/shell_words.hpp"
#include "runtime/session/session.hpp"

namespace rollsense::cli {
namespace {

// After a failure that came after the script's end (a cleanup, a device's shutdown): nothing left to resume.
constexpr const char* kAfterTheEnd = "the script ran to its end and its trials are on disk; what failed came after it "
                                     "(above): a resume would record nothing";

const char* kHelp = R"(usage: rollsense run SCRIPT [options]
       rollsense run SCRIPT --help      the settings SCRIPT declares (runs no trial)
       rollsense run SCRIPT --check [options]   check the settings, run nothing

Run a Lua roll procedure on a robot profile. With the default `sim` profile
the hand, the objects and the barometers are simulated on a virtual clock (the
run goes as fast as the CPU allows and is deterministic for a seed); with a
hardware profile the same script drives the real hand on the monotonic clock.

options:
  --profile NAME|FILE   robot profile (share/profiles/NAME.lua); default: sim
  --out DIR             dataset folder for recorded trials and outputs: new,
                        empty, or with --resume the run's dataset (a file,
                        or a folder holding other files, is refused: the run
                        would write over them); default: runs/<script>-<date>-<time>
  --resume              continue the dataset in --out (a folder that does not
                        exist is refused): trials already on disk
                        are kept and skipped; the result equals an uninterrupted run.
                        Refused when script, profile, --set or --seed differ
                        from the run that recorded it (run-config.csv), and
                        for a shard's dataset without its --shard K/N (a
                        refused folder is left as it was). The earlier run's
                        run-info.csv is kept as run-info.N.csv
  --check               check what the run checks before its first trial
                        (the profile with its overrides, each device's plugin
                        and its parameters against the plugin's schema, the
                        script's declared settings against --set, the other
                        options, --out), then stop: nothing created, no device
                        configured, no trial (docs/scripting.md, Settings)
  --seed N              run seed, 0 to 2^63-1 (per-trial seeds derive from it);
                        default: 1, or, replaying a dataset, the seed it was
                        recorded with
  --shard K/N           record only shard K of N (0 <= K < N, N >= 2): the
                        trials whose index in the run is K mod N; the shards'
                        datasets are joined with 'rollsense merge'
                        (docs/cluster.md)
  --set KEY=VALUE       a setting (repeatable; of one key given twice, the later
                        holds): a key starting with a profile
                        entry overrides it (plugin parameters:
                        devices.NAME.params.KEY, e.g. devices.tactile.params.kernel_fwhm=5;
                        a list in braces, quoted for the shell:
                        'devices.tactile.params.cell_angles={-30,0,30}');
                        any other key is a script setting: plain for the
                        script (runs=2), MODULE.KEY for a Lua module
                        (etroll.clamp_current=150); checked before the first
                        trial when the script declares its settings; a
                        --set the script, the profile or a plugin refuses is a
                        bad command line (exit 2)
  --plugin-path DIR     search plugins here first (repeatable)
  --time-limit S        cancel the run after S seconds of run time (0, the
                        default: no limit)
  --slice-limit-ms MS   stop a script (or profile) that runs MS ms without
                        waiting: its failure, at its file:line (default 5000)
  --memory-limit-mb MB  Lua heap cap, and the most a recording may hold in
                        memory (default 256)
  --commit-every N      trials per durable group commit (0, the default: 1 on
                        hardware, 64 in simulation)
  --no-progress         no progress bar (it is off anyway when stderr is not a terminal)
  --live[=PORT]         serve a live view of the run in the browser on
                        http://127.0.0.1:PORT/ (default port 8027; 0: any free
                        port, printed): signals, joints, progress, step, faults,
                        identification; read-only (docs/live-view.md)
  --live-bind ADDR      listen on ADDR instead of 127.0.0.1 (warns: anyone who
                        can reach ADDR can watch the run)
  -v, --verbose         debug messages;   -q, --quiet   no info messages: warnings, errors
                        and the closing summary (where the results are))";

std::string default_out(const std::filesystem::path& script) {
    std::time_t t = std::time(nullptr);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&t));
    return "runs/" + script.stem().string() + "-" + stamp;
}

// --slice-limit-ms and --memory-limit-mb; ranges: a zero budget would silently switch a protection off.
runtime::SandboxLimits sandbox_limits_of(const Args& args) {
    runtime::SandboxLimits limits;
    limits.max_slice_ms = static_cast<double>(args.unsigned_option("--slice-limit-ms", 5000, 1, 3'600'000));
    limits.memory_bytes = args.unsigned_option("--memory-limit-mb", 256, 1, 1u << 20) * 1024 * 1024;
    return limits;
}

// `rollsense run SCRIPT --help`: the command's options, then the script's settings
// (found by running the script's top under the run's limits).
int print_script_help(const std::vector<std::string>& positionals, const Args& args) {
    // The script's error alone, not after the whole usage text.
    std::optional<Result<std::vector<script_settings::Declaration>>> declared;
    std::string stopped_at;  // where reading the declarations stopped: a call where trials could begin
    if (positionals.size() == 1)
        declared = script_settings::declared_by(resolve_script(positionals[0]), share_dir(), sandbox_limits_of(args),
                                                &stopped_at);
    if (declared && !*declared) throw StatusError(Status{declared->error()});
    std::printf("%s\n\nexit codes (rollsense --help):\n%s", kHelp, exit_code_table().c_str());
    if (!declared) return kExitOk;
    const char* script = positionals[0].c_str();
    if ((*declared)->empty() && stopped_at.empty())
        std::printf("\n%s declares no settings (rs.settings); its --set keys are not checked before it runs\n", script);
    else if ((*declared)->empty())
        std::printf("\n%s declares no settings before %s, where reading them stops (trials could begin there);\n"
                    "declare them with rs.settings before it, so that --set is checked before anything runs\n",
                    script, stopped_at.c_str());
    else
        std::printf("\nsettings of %s (--set KEY=VALUE; default shown)%s:\n%s", script,
                    stopped_at.empty() ? "" : (", declared before " + stopped_at).c_str(),
                    script_settings::describe(**declared).c_str());
    return kExitOk;
}

// --live (the default port), --live=PORT, --live-bind ADDR; nothing without --live.
// (Args::option would take the word after a bare --live as its value.)
std::optional<live::LiveOptions> live_options_of(const std::vector<std::string>& argv, const Args& args) {
    live::LiveOptions o;
    bool wanted = false;
    for (const auto& a : argv) {
        if (a == "--live") wanted = true;
        if (!a.starts_with("--live=")) continue;
        const std::string port = a.substr(7);
        auto p = csv::parse_unsigned(port, 65535, "--live");
        if (!p) throw UsageError("--live=PORT expects a port number from 0 to 65535, got '" + port + "'");
        o.port = static_cast<std::uint16_t>(*p);
        wanted = true;
    }
    if (auto bind = args.option("--live-bind"); !bind.empty()) {
        if (!wanted) throw UsageError("--live-bind needs --live (it says where the live view listens)");
        if (auto s = live::HttpServer::check_address(bind); !s.ok()) throw UsageError("--live-bind: " + s.message());
        o.address = bind;
        if (bind != "127.0.0.1" && bind != "::1")
            log_warning("rollsense", "--live-bind " + bind + ": the live view can be watched from other machines "
                                     "(it is read-only, but shows the run's data to anyone who can reach it)");
    }
    if (!wanted) return std::nullopt;
    return o;
}

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    const std::vector<std::string> valued = {"--profile", "--out", "--seed", "--shard", "--set", "--plugin-path",
                                             "--time-limit", "--slice-limit-ms", "--memory-limit-mb", "--commit-every",
                                             "--live-bind"};
    auto pos = args.positionals(valued);
    if (args.wants_help()) return print_script_help(pos, args);
    args.reject_unknown({"--profile", "--out", "--resume", "--check", "--seed", "--shard", "--set", "--plugin-path",
                         "--time-limit", "--slice-limit-ms", "--memory-limit-mb", "--commit-every", "--no-progress",
                         "-v", "--verbose", "-q", "--quiet", "--live", "--live-bind"});
    if (pos.size() != 1) throw UsageError("expects one SCRIPT (see --help)");
    setup_logging(args);

    runtime::SessionOptions o;
    o.script = resolve_script(pos[0]);
    o.share_dir = share_dir();
    if (auto p = args.option("--profile"); !p.empty()) o.profile = p;
    o.resume = args.flag("--resume");
    auto out = args.option("--out");
    if (out.empty() && o.resume) throw UsageError("--resume needs --out DIR (the dataset to continue)");
    o.out_dir = out.empty() ? default_out(o.script) : out;
    // Up to 2^63 - 1: rs.seed() gives it to the script as a Lua integer (review: larger ones read negative).
    o.seed = args.unsigned_option("--seed", 1, 0, INT64_MAX);
    if (auto shard = args.option("--shard"); !shard.empty()) {
        auto parsed = parse_shard(shard, "--shard");
        if (!parsed) throw UsageError(parsed.error().message);
        o.shard = *parsed;
    }
    const bool check_only = args.flag("--check");  // every option checked as for a run; no folder made, no device, no trial
    if (auto st = check_out_folder(o.out_dir, o.resume, o.shard); !st) {
        if (st.code() == ErrorCode::invalid_argument) throw UsageError(st.message());
        std::fprintf(stderr, "rollsense run: %s\n", st.error().describe().c_str());  // a damaged dataset: 3, or 5
        return exit_code_for(st.code(), kExitConfig);
    }
    // The options that decide what is recorded: in run-config.csv and in the resume command.
    std::vector<std::pair<std::string, std::string>> deciding;
    if (!args.option("--profile").empty()) deciding.emplace_back("--profile", args.option("--profile"));
    if (!args.option("--seed").empty()) deciding.emplace_back("--seed", args.option("--seed"));
    if (o.shard) deciding.emplace_back("--shard", o.shard->text());  // not in run-config.csv: a part of the run
    SetOptions sets;
    for (const auto& kv : args.options("--set")) {
        if (auto s = o.settings.add(kv); !s.ok()) throw UsageError(s.message());
        sets.emplace_back(kv.substr(0, kv.find('=')), kv.substr(kv.find('=') + 1));
        deciding.emplace_back("--set", kv);
    }
    for (const auto& p : args.options("--plugin-path")) {
        o.plugin_path.emplace_back(p);
        deciding.emplace_back("--plugin-path", p);
    }
    o.sandbox = sandbox_limits_of(args);
    // Ranges: a zero or negative budget would silently switch a protection off.
    o.time_limit_s = args.number_option("--time-limit", 0, 0, 1e9);
    o.commit_every = args.unsigned_option("--commit-every", 0, 0, 1'000'000);
    // Before run-config.csv: it records the seed the run uses (review: a replay's said 1, and its resume was refused).
    if (args.option("--seed").empty())
        if (auto recorded = recorded_seed(o)) {
            o.seed = recorded->seed;
            log_info("rollsense", "replaying " + recorded->dataset.string() + ": the run uses the recording's seed " +
                                      std::to_string(o.seed) + " (so its trials line up; give --seed N for another)");
        }
    o.run_config = run_config_of(o.script, o.profile, runtime::resolve_profile_path(o.profile, o.share_dir), o.share_dir,
                                 o.seed, sets);
    // A --resume whose options differ from the recording's is the command line's error (2), before anything opens;
    // a run-config.csv that cannot be read is the dataset's (3, or 5 for a read the system refuses).
    if (o.resume && std::filesystem::exists(o.out_dir / kRunConfigFile))
        if (auto s = check_resume_config(o.out_dir, o.run_config); !s.ok()) {
            if (s.code() == ErrorCode::invalid_argument) throw UsageError(s.message());
            std::fprintf(stderr, "rollsense run: %s\n", s.error().describe().c_str());
            return exit_code_for(s.code(), kExitConfig);
        }
    if (check_only) {  // the folder and resume checks above only read; nothing further is opened
        live_options_of(argv, args);  // refused here as in a run
        return check_run_settings(o, pos[0]);
    }
    o.digital_lines = hal::gpio_digital_lines();
    o.command_line = "rollsense run " + shell_join(argv);  // as a shell reads it back (review: paths with spaces)
    // The watchdog's way out (three Ctrl-C, a script stuck in one C call) ends the process inside the run.
    o.way_on = {"the trials saved stay on disk; a resume runs the same script again (after a script stuck in one "
                "call, fix it and record into a new --out)\ncontinue with: " + resume_command(pos[0], o.out_dir, deciding) +
                    "\n",
                std::string(kAfterTheEnd) + "\n"};  // stuck in its cleanup (diff review: it offered a resume)

    // Review: a resume into a folder another run is recording failed as a run ("failed: 0 trials saved, N already
    // on disk", "continue with: ... --resume", exit 1). Another run's lock is the command line's refusal, before
    // anything runs (the live view included); other lock failures (permissions, NFS) are left to the dataset
    // writer, which says them as I/O errors. The writer's own lock still decides: another run may start between.
    if (std::error_code ec; std::filesystem::is_directory(o.out_dir, ec))
        if (auto busy = DirectoryLock::acquire(o.out_dir); !busy && busy.error().code == ErrorCode::state_error)
            throw UsageError(busy.error().message);

    ProgressBar bar(!args.flag("--no-progress"));  // before the live view's threads (it wraps the log sink)
    std::unique_ptr<live::LiveView> view;
    if (auto live_options = live_options_of(argv, args)) {
        auto started = live::LiveView::start(*live_options, o);
        if (!started) throw StatusError(Status{started.error()});
        view = std::move(*started);
        std::fprintf(stderr, "live view: %s\n", view->where().c_str());
    }
    o.on_progress = [&bar, observer = std::move(o.on_progress)](std::size_t done, std::size_t total,
                                                                 const std::string& label, double run_clock_s) {
        bar.update(done, total, label, run_clock_s);
        if (observer) observer(done, total, label, run_clock_s);
    };

    std::error_code ec;
    const bool out_existed = std::filesystem::exists(o.out_dir, ec);
    const auto out_before = folder_state(o.out_dir);
    runtime::RunSummary summary;
    {
        runtime::Session session(o);
        summary = session.run();
    }  // the dataset's folder lock is released here
    bar.finish();
    if (view) view->finished(summary);
    // The trials the dataset held before this run and still holds. The kernel counts those the script skipped
    // (rs.has_trial); a resume that stopped before its script reached them (a device that failed at activation)
    // leaves them on disk all the same. Read only then: a run that ended well counted them all.
    const std::size_t listed = o.resume && !summary.status.ok() ? trials_listed(o.out_dir) : 0;
    const std::size_t already = std::max(summary.trials_skipped, listed - std::min(listed, summary.trials_saved));
    // The error first, once; then the summary, where the results are and the way on.
    if (!summary.status.ok()) log_error("rollsense", summary.status.error().describe());
    // Review: --shard 120/150 of a 108-trial run recorded nothing, and said done.
    if (summary.status.ok() && o.shard && summary.trials_saved + already == 0)
        log_warning("rollsense", "shard " + o.shard->text() + " holds no trial of this run (it has fewer than " +
                                     std::to_string(o.shard->index + 1) + " trials, or the script records none): "
                                     "split it into fewer shards");
    std::fprintf(stderr, "%s: %zu trials saved, %zu already on disk; %.1f s robot time in %.2f s wall\n",
                 summary.status.ok() ? "done" : (summary.cancelled ? "cancelled" : "failed"), summary.trials_saved,
                 already, summary.run_time_s, summary.wall_time_s);
    if (summary.control_timing && summary.control_timing->periods > 0)
        std::fprintf(stderr, "control loop: %s\n", summary.control_timing->describe().c_str());
    // A run that failed before its first trial leaves no empty folder behind.
    const bool removed = !summary.status.ok() && !out_existed && summary.trials_saved + already == 0 &&
                         remove_empty_dataset(o.out_dir);
    // Not for a run refused before it wrote anything (another run's dataset, --out a file).
    const bool wrote = summary.trials_saved + already > 0 || folder_state(o.out_dir) != out_before;
    if (!removed && wrote && std::filesystem::exists(o.out_dir, ec))
        std::fprintf(stderr, "results: %s\n", o.out_dir.c_str());
    if (summary.status.ok() || summary.trials_saved + already == 0) return exit_code_for(summary.status.code());
    // However it stopped, the saved trials stay: the way on. After an analysis that failed of itself, a resume would
    // only run it again on the same trials; one stopped (Ctrl-C, --time-limit) or cut short by the disk can go on.
    const auto analysed = runtime::lua_api::unfinished_analysis();
    // Review: a device that failed to shut down after the script's end (a plugin's on_deactivate threw) was
    // followed by "continue with: ... --resume", which would record nothing.
    if (summary.script_ended && summary.status.code() != ErrorCode::io_error)
        std::fprintf(stderr, "%s\n", kAfterTheEnd);
    else if (analysed && !summary.cancelled && summary.status.code() != ErrorCode::io_error)
        std::fprintf(stderr, "the analysis failed, not the recording: the %zu trials of %s are on disk (--resume "
                             "would run the same analysis on them again)\nanalyse them with: %s (options such as "
                             "--folds, --classifier: their --help)\n",
                     trials_listed(*analysed), analysed->c_str(), analysis_commands(*analysed, o.out_dir).c_str());
    // A refused setup or --set (bad_setting) fails the same way when resumed: its message names the way out.
    else if (summary.status.code() != ErrorCode::bad_setting) {
        // Review: the advice was a dead end for a script's own bug (an API misuse, a limit it commanded past, too).
        if (!summary.cancelled && summary.status.code() != ErrorCode::io_error)
            std::fprintf(stderr, "a resume runs the same script again and refuses an edited one (run-config.csv): it "
                                 "helps when the cause was outside the script (the hand, an object, a device); a fixed "
                                 "script records into a new --out\n");
        std::fprintf(stderr, "continue with: %s\n", resume_command(pos[0], o.out_dir, deciding).c_str());
    }
    return exit_code_for(summary.status.code());
}

const Registration reg{{"run", "run a Lua roll procedure on a robot profile", kHelp, &run, true}};

}  // namespace
}  // namespace rollsense::cli
