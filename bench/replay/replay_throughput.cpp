// Replay throughput, in trials per second (not run by ctest):
//
//   replay_throughput [--trials N] [--samples S] [--session-runs R]
//
// 1. plugin: a dataset of N trials of S samples (3 channels and the finger,
//    written by the SDK's writer) played by the ReplaySensor class alone:
//    each trial's file read on demand, every sample served and roll-checked.
//    Reading the files alone (DatasetReader::load) is printed beside it.
// 2. session: scripts/paper_experiment.lua recorded on the mock profile
//    (9 objects x 3 speeds x R runs), then re-run on the replay profile, both
//    on the virtual clock: the end-to-end replay rate a user sees.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "replay_sensor.hpp"
#include "rollsense/dataset.hpp"
#include "runtime/session/session.hpp"

using namespace rollsense;
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void write_dataset(const fs::path& dir, int trials, int samples) {
    DatasetInfo info;
    info.channels = {"ch1", "ch2", "ch3"};
    info.joints = {"sensing_finger"};
    info.profile = "bench";
    auto w = DatasetWriter::open(dir, info, DatasetOpenMode::create);
    if (!w) throw StatusError(w.status());
    (*w)->set_commit_every(64);
    for (int t = 0; t < trials; ++t) {
        TrialData d;
        d.channels.resize(3);
        d.joints.resize(1);
        for (int i = 0; i < samples; ++i) {
            d.time.push_back(std::round(i / 31.1 * 1e6) / 1e6);
            for (int c = 0; c < 3; ++c) d.channels[c].push_back(0.25 * std::exp(-0.5 * std::pow((i - 40.0 * (c + 1)) / 9.0, 2)));
            d.joints[0].push_back(-44.0 + 88.0 * i / samples);
            d.valid.push_back(1);
        }
        TrialRecord r;
        r.info.id = "T" + std::to_string(t);
        r.info.object = "C1";
        r.info.speed = "10";
        r.info.repetition = t + 1;
        throw_if_error((*w)->add_trial(r, d));
    }
    throw_if_error((*w)->flush());
}

void bench_plugin(const fs::path& dir, int trials, int samples) {
    write_dataset(dir, trials, samples);
    auto reader = DatasetReader::open(dir);
    if (!reader) throw StatusError(reader.status());
    auto t0 = std::chrono::steady_clock::now();
    std::size_t loaded = 0;
    for (const auto& r : reader->trials()) loaded += reader->load(r)->samples();
    const double load_s = seconds_since(t0);

    ParamSet params = value_or_throw(validate_params(plugins::replay::replay_schema(),
                                                     {{"dataset", dir.string()}, {"select", std::string("order")}},
                                                     "bench"));
    plugins::replay::ReplaySensor s;
    PluginContext ctx;
    ctx.instance = "bench";
    throw_if_error(s.on_configure(params, ctx));
    throw_if_error(s.on_activate());
    std::vector<std::string> names{"sensing_finger"};
    std::vector<JointState> states(1);
    std::size_t served = 0, invalid = 0;
    t0 = std::chrono::steady_clock::now();
    for (int t = 0; t < trials; ++t) {
        TrialInfo info;
        info.id = "T" + std::to_string(t);
        throw_if_error(s.begin_trial(info));
        throw_if_error(s.start_recording(SampleInput{0.0, &names, &states}));
        Frame f;
        for (int i = 0; i < samples; ++i) {
            const double time = std::round(i / 31.1 * 1048576.0) / 1048576.0;
            states[0].position = -44.0 + 88.0 * i / samples;
            f.values.assign(3, 0.0);
            f.valid = true;
            throw_if_error(s.read(SampleInput{time, &names, &states}, f));
            ++served;
            invalid += f.valid ? 0 : 1;
        }
        throw_if_error(s.stop_recording());
        throw_if_error(s.end_trial());
    }
    const double play_s = seconds_since(t0);
    std::printf("plugin   %d trials x %d samples: replayed in %.3f s = %.0f trials/s (%.0f samples/s, %zu invalid)\n",
                trials, samples, play_s, trials / play_s, served / play_s, invalid);
    std::printf("         reading the trial files alone: %.3f s = %.0f trials/s (%zu samples)\n", load_s,
                trials / load_s, loaded);
}

runtime::RunSummary run_session(const std::string& profile, const fs::path& out, int runs, const fs::path& dataset) {
    runtime::SessionOptions o;
    o.script = fs::path(ROLLSENSE_SOURCE_DIR) / "scripts/paper_experiment.lua";
    o.profile = profile;
    o.share_dir = ROLLSENSE_SHARE_DIR;
    o.out_dir = out;
    o.seed = 3;
    o.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    throw_if_error(o.settings.add("runs=" + std::to_string(runs)));
    throw_if_error(o.settings.add("analyse=false"));  // time the trials, not the script's evaluation
    if (!dataset.empty()) throw_if_error(o.settings.add("dataset=" + dataset.string()));
    runtime::Session session(o);
    auto summary = session.run();
    throw_if_error(summary.status);
    return summary;
}

void bench_session(const fs::path& dir, int runs) {
    auto rec = run_session("mock", dir / "recorded", runs, {});
    auto rep = run_session("replay", dir / "replayed", runs, dir / "recorded");
    std::printf("session  paper_experiment.lua, %zu trials (virtual clock, %.0f s of run time in all):\n",
                rec.trials_saved, rec.run_time_s);
    std::printf("         recorded on mock:   %.3f s wall = %.1f trials/s\n", rec.wall_time_s,
                rec.trials_saved / rec.wall_time_s);
    std::printf("         replayed on replay: %.3f s wall = %.1f trials/s\n", rep.wall_time_s,
                rep.trials_saved / rep.wall_time_s);
}

}  // namespace

int main(int argc, char** argv) {
    int trials = 1350, samples = 150, runs = 2;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--trials")) trials = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--samples")) samples = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--session-runs")) runs = std::atoi(argv[i + 1]);
        else {
            std::fprintf(stderr, "usage: %s [--trials N] [--samples S] [--session-runs R]\n", argv[0]);
            return 2;
        }
    }
    const fs::path dir = fs::temp_directory_path() / ("rollsense-replay-bench-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    int rc = 0;
    try {
        bench_plugin(dir / "plugin", trials, samples);
        if (runs > 0) bench_session(dir / "session", runs);
    } catch (const StatusError& e) {
        std::fprintf(stderr, "replay_throughput: %s\n", e.what());
        rc = 1;
    }
    fs::remove_all(dir);
    return rc;
}
