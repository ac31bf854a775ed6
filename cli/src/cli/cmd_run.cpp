// rollsense run SCRIPT: run a roll procedure on a robot profile.
#include <cstdio>
#include <ctime>
#include <string>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "cli/paths.hpp"
#include "cli/recorded_seed.hpp"
#include "rollsense/hal/gpio.hpp"
#include "rollsense/log.hpp"
#include "runtime/session/session.hpp"

namespace rollsense::cli {
namespace {

const char* kHelp = R"(usage: rollsense run SCRIPT [options]

Run a Lua roll procedure on a robot profile. With the default `sim` profile
the hand, the objects and the barometers are simulated on a virtual clock (the
run goes as fast as the CPU allows and is deterministic for a seed); with a
hardware profile the same script drives the real hand on the monotonic clock.

options:
  --profile NAME|FILE   robot profile (share/profiles/NAME.lua); default: sim
  --out DIR             dataset folder for recorded trials and outputs;
                        default: runs/<script>-<date>-<time>
  --resume              continue the dataset in --out: trials already on disk
                        are kept and skipped; the result equals an uninterrupted run
  --seed N              run seed (per-trial seeds derive from it); default: 1,
                        or, replaying a dataset, the seed it was recorded with
  --set KEY=VALUE       a setting read by the profile or script (repeatable);
                        a dotted key overrides a profile entry, e.g.
                        --set devices.tactile.params.kernel_fwhm=5
  --plugin-path DIR     search plugins here first (repeatable)
  --time-limit S        cancel the run after S seconds of run time
  --slice-limit-ms MS   cancel a script that runs MS ms without waiting (default 5000)
  --memory-limit-mb MB  Lua heap cap (default 256)
  --commit-every N      trials per durable group commit (default 1 on hardware,
                        64 in simulation)
  --no-progress         no progress bar (it is off anyway when stderr is not a terminal)
  -v, --verbose         debug messages;   -q, --quiet   warnings and errors only)";

std::string default_out(const std::filesystem::path& script) {
    std::time_t t = std::time(nullptr);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&t));
    return "runs/" + script.stem().string() + "-" + stamp;
}

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    args.reject_unknown({"--profile", "--out", "--resume", "--seed", "--set", "--plugin-path", "--time-limit",
                         "--slice-limit-ms", "--memory-limit-mb", "--commit-every", "--no-progress", "-v",
                         "--verbose", "-q", "--quiet"});
    const std::vector<std::string> valued = {"--profile", "--out", "--seed", "--set", "--plugin-path",
                                             "--time-limit", "--slice-limit-ms", "--memory-limit-mb", "--commit-every"};
    auto pos = args.positionals(valued);
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
    o.seed = args.unsigned_option("--seed", 1, 0, UINT64_MAX);
    for (const auto& kv : args.options("--set"))
        if (auto s = o.settings.add(kv); !s.ok()) throw UsageError(s.message());
    for (const auto& p : args.options("--plugin-path")) o.plugin_path.emplace_back(p);
    // Ranges: a zero or negative budget would silently switch a protection off.
    o.time_limit_s = args.number_option("--time-limit", 0, 0, 1e9);
    o.sandbox.max_slice_ms = static_cast<double>(args.unsigned_option("--slice-limit-ms", 5000, 1, 3'600'000));
    o.sandbox.memory_bytes = args.unsigned_option("--memory-limit-mb", 256, 1, 1u << 20) * 1024 * 1024;
    o.commit_every = args.unsigned_option("--commit-every", 0, 0, 1'000'000);
    o.progress = !args.flag("--no-progress");
    o.digital_lines = hal::gpio_digital_lines();
    if (args.option("--seed").empty())
        if (auto recorded = recorded_seed(o)) {
            o.seed = recorded->seed;
            log_info("rollsense", "replaying " + recorded->dataset.string() + ": the run uses the recording's seed " +
                                      std::to_string(o.seed) + " (so its trials line up; give --seed N for another)");
        }
    o.command_line = "rollsense run";
    for (const auto& a : argv) o.command_line += " " + a;

    runtime::Session session(o);
    auto summary = session.run();
    std::fprintf(stderr, "%s: %zu trials saved, %zu already on disk; %.1f s robot time in %.2f s wall\n",
                 summary.status.ok() ? "done" : (summary.cancelled ? "cancelled" : "failed"), summary.trials_saved,
                 summary.trials_skipped, summary.run_time_s, summary.wall_time_s);
    if (summary.control_timing && summary.control_timing->periods > 0)
        std::fprintf(stderr, "control loop: %s\n", summary.control_timing->describe().c_str());
    if (summary.trials_saved + summary.trials_skipped > 0 || std::filesystem::exists(o.out_dir))
        std::fprintf(stderr, "results: %s\n", o.out_dir.c_str());
    if (!summary.status.ok()) {
        log_error("rollsense", summary.status.error().describe());
        if (summary.cancelled && summary.trials_saved > 0)
            std::fprintf(stderr, "continue with: rollsense run %s --out %s --resume%s\n", pos[0].c_str(),
                         o.out_dir.c_str(), args.option("--seed").empty() ? "" : (" --seed " + args.option("--seed")).c_str());
    }
    return exit_code_for(summary.status.code());
}

const Registration reg{{"run", "run a Lua roll procedure on a robot profile", kHelp, &run}};

}  // namespace
}  // namespace rollsense::cli
