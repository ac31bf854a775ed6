// Calibration bench of the sim sensor (docs/simulation.md, "Calibration"):
// runs the stock experiment (9 objects × 3 speeds × 50 runs) through the plugin
// class exactly as the roll script drives it, and prints every calibration
// target of simulation.md §6 beside the paper's value, plus the cost per frame.
//
//   sim_calibration [--runs N] [--seed S] [--noise-trials N] [--features out.csv] [--set key=value ...]
//   sim_calibration --dataset DIR [--features out.csv]
//
// --set overrides a sim parameter (any key of the plugin's schema), which is how
// the free parameters were fitted. --features writes the 13 features of every
// trial for an external classifier check (bench/sim/check_classifier.py).
// --dataset judges a dataset recorded by `rollsense run` (manifest.csv + trial
// CSVs with ch1..ch3 columns) by the same rule: the cross-check through the kernel.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <ctime>
#include <fstream>
#include <map>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include "rng.hpp"
#include "roll_driver.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/features.hpp"
#include "sim_schema.hpp"
#include "sim_sensor.hpp"

using namespace rollsense;
using namespace rollsense::sim;

namespace {

struct Options {
    int runs = 50;
    int noise_trials = 1002;  // empty-hand recordings for the noise figure (a multiple of 3: per speed)
    std::uint64_t seed = 2024;
    std::string features;
    std::string dataset;
    std::map<std::string, ParamValue> overrides;
};

bool parse(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--runs") o.runs = std::stoi(next());
        else if (a == "--seed") o.seed = std::stoull(next());
        else if (a == "--noise-trials") o.noise_trials = std::max(3, std::stoi(next()));
        else if (a == "--features") o.features = next();
        else if (a == "--dataset") o.dataset = next();
        else if (a == "--set") {
            const std::string kv = next();
            const auto eq = kv.find('=');
            if (eq == std::string::npos) {
                std::fprintf(stderr, "--set expects key=value, got '%s'\n", kv.c_str());
                return false;
            }
            const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
            // Integers stay integers (device_seed, baseline_samples), true/false booleans, anything else a number or a string.
            char* end = nullptr;
            const long long as_int = std::strtoll(value.c_str(), &end, 10);
            if (end && *end == '\0' && (key == "device_seed" || key == "baseline_samples")) {
                o.overrides[key] = static_cast<std::int64_t>(as_int);
            } else {
                const double d = std::strtod(value.c_str(), &end);
                if (end && *end == '\0') o.overrides[key] = d;
                else if (value == "true" || value == "false") o.overrides[key] = value == "true";
                else o.overrides[key] = value;
            }
        } else {
            std::fprintf(stderr,
                         "usage: %s [--runs N] [--seed S] [--noise-trials N] [--features out.csv] [--set key=value ...]\n"
                         "       %s --dataset DIR [--features out.csv]   (a dataset recorded by rollsense run)\n",
                         argv[0], argv[0]);
            return false;
        }
    }
    return true;
}

// The paper's validity rule and 13 features: the SDK's pipeline with its
// defaults (smoothing factor 0.05 per channel, 5 % walk, max > 0.01, complete
// peaks), the same code `rollsense features` and the classifier use.
Result<features::TrialFeatures> judge_trial(features::FeatureExtractor& fx,
                                            const std::array<std::vector<double>, 3>& raw) {
    const std::array<std::span<const double>, 3> spans{raw[0], raw[1], raw[2]};
    return fx.extract(std::span<const std::span<const double>>(spans));
}

// Every channel's maximum above the validity threshold (the object touched all three).
bool all_above_threshold(const features::TrialFeatures& tf, const features::FeatureSettings& settings) {
    return std::all_of(tf.channels.begin(), tf.channels.end(),
                       [&](const features::ChannelPeak& c) { return c.amplitude > settings.min_amplitude; });
}

struct Stats {
    std::vector<double> v;
    void add(double x) { v.push_back(x); }
    double mean() const { return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / v.size(); }
    double sd() const {
        if (v.size() < 2) return 0.0;
        const double m = mean();
        double s = 0.0;
        for (double x : v) s += (x - m) * (x - m);
        return std::sqrt(s / (v.size() - 1));
    }
    double min() const { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }
    double max() const { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }
};

// Judge every trial of a recorded dataset (the kernel's run through the plugin).
int judge_dataset(const Options& opt) {
    const std::filesystem::path dir = opt.dataset;
    auto manifest = csv::Reader::open(dir / "manifest.csv");
    if (!manifest) {
        std::fprintf(stderr, "%s\n", manifest.error().describe().c_str());
        return 1;
    }
    auto c_file = manifest->column("file");
    auto c_object = manifest->column("object");
    auto c_speed = manifest->column("speed");
    auto c_id = manifest->column("trial_id");
    if (!c_file || !c_object || !c_speed || !c_id) {
        std::fprintf(stderr, "%s: manifest lacks trial_id/file/object/speed columns\n", dir.string().c_str());
        return 1;
    }
    std::map<std::string, Stats> samples;
    std::map<std::string, std::pair<int, int>> per_object;  // clean, total
    int trials = 0, clean = 0, cyl = 0, cyl_clean = 0, all_above = 0;
    std::string features_csv =
        "trial_id,object,speed,repetition,clean,reason,F1,F2,F3,F4,F5,F6,F7,F8,F9,F10,F11,F12,F13\n";
    std::vector<std::string> row, fields;
    features::FeatureExtractor fx;
    while (true) {
        auto more = manifest->next(row);
        if (!more) {
            std::fprintf(stderr, "%s\n", more.error().describe().c_str());
            return 1;
        }
        if (!more.value()) break;
        auto trial = csv::Reader::open(dir / row[*c_file]);
        if (!trial) {
            std::fprintf(stderr, "%s\n", trial.error().describe().c_str());
            return 1;
        }
        std::array<std::size_t, 3> cols{};
        for (std::size_t c = 0; c < 3; ++c) {
            auto idx = trial->column("ch" + std::to_string(c + 1));
            if (!idx) {
                std::fprintf(stderr, "%s\n", idx.error().describe().c_str());
                return 1;
            }
            cols[c] = idx.value();
        }
        std::array<std::vector<double>, 3> ch;
        while (true) {
            auto got = trial->next(fields);
            if (!got || !got.value()) break;
            for (std::size_t c = 0; c < 3; ++c) {
                auto v = trial->number(fields, cols[c]);
                ch[c].push_back(v ? v.value() : std::nan(""));
            }
        }
        const std::string& object = row[*c_object];
        const auto verdict = judge_trial(fx, ch);
        if (!verdict) {
            std::fprintf(stderr, "%s: %s\n", row[*c_id].c_str(), verdict.error().describe().c_str());
            return 1;
        }
        ++trials;
        samples[row[*c_speed]].add(static_cast<double>(ch[0].size()));
        auto& po = per_object[object];
        ++po.second;
        if (all_above_threshold(*verdict, fx.settings())) ++all_above;
        if (object[0] == 'C') ++cyl;
        if (verdict->clean) {
            ++clean;
            ++po.first;
            if (object[0] == 'C') ++cyl_clean;
        }
        std::vector<std::string> out{row[*c_id], object, row[*c_speed], "0", verdict->clean ? "1" : "0",
                                     verdict->reason};
        for (double f : verdict->values) out.push_back(std::isfinite(f) ? csv::format_number(f) : "");
        csv::append_row(features_csv, out);
    }
    std::printf("dataset %s: %d trials\n", dir.string().c_str(), trials);
    for (const auto& [speed, s] : samples)
        std::printf("samples per trial, speed %s: %.1f +- %.1f [%g..%g]\n", speed.c_str(), s.mean(), s.sd(), s.min(), s.max());
    std::printf("clean %d/%d = %.1f %% (cylinders %d/%d, polygons %d/%d); every channel > 0.01 in %d/%d\n", clean, trials,
                100.0 * clean / std::max(1, trials), cyl_clean, cyl, clean - cyl_clean, trials - cyl, all_above, trials);
    std::printf("clean per object:");
    for (const auto& [o, n] : per_object) std::printf(" %s %d/%d", o.c_str(), n.first, n.second);
    std::printf("\n");
    if (!opt.features.empty()) {
        std::ofstream(opt.features) << features_csv;
        std::printf("features written to %s\n", opt.features.c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    if (!parse(argc, argv, opt)) return 2;
    if (!opt.dataset.empty()) return judge_dataset(opt);
    auto params = validate_params(sim_schema(), opt.overrides, "sim_calibration --set");
    if (!params) {
        std::fprintf(stderr, "%s\n", params.error().describe().c_str());
        return 2;
    }
    PluginContext ctx;
    ctx.instance = "tactile";
    ctx.share_dir = ROLLSENSE_SHARE_DIR;
    SimSensor sensor;
    if (auto st = sensor.on_configure(params.value(), ctx); !st) {
        std::fprintf(stderr, "%s\n", st.error().describe().c_str());
        return 1;
    }

    const std::vector<std::string> objects{"C1", "C2", "C3", "S1", "S2", "P1", "P2", "H1", "H2"};
    const std::vector<int> speeds{10, 15, 20};
    std::map<int, Stats> samples_per_speed;
    std::map<std::string, int> clean_per_object, total_per_object;
    std::map<std::string, int> reasons;
    int trials = 0, clean = 0, all_above = 0, cyl_clean = 0, cyl_total = 0, poly_clean = 0, poly_total = 0;
    int rejected_low_amplitude = 0;
    std::map<std::string, std::map<int, Stats>> ch13_interval;  // cylinders: s between ch1 and ch3 maxima
    std::map<std::string, Stats> amplitude;
    std::string features_csv =
        "trial_id,object,speed,repetition,clean,reason,F1,F2,F3,F4,F5,F6,F7,F8,F9,F10,F11,F12,F13\n";
    double sim_seconds = 0.0;
    long frames = 0;
    std::map<bool, double> kind_seconds;
    std::map<bool, long> kind_frames;
    bench::Recording rec;
    features::FeatureExtractor fx;

    for (const auto& object : objects) {
        long index_in_mount = 0;  // the stock script's protocol: each object mounted once for all its runs
        for (int speed : speeds) {
            for (int rep = 1; rep <= opt.runs; ++rep) {
                const std::string id = object + "-s" + std::to_string(speed) + "-r" + std::to_string(rep);
                TrialInfo trial{id, object, std::to_string(speed), rep, mix64(opt.seed ^ label_hash(id)),
                                {{"mount", object + "-1"}, {"index_in_mount", std::to_string(index_in_mount++)}}};
                // The script and actuator side: speed jitter ≈ 1 %, overhead ≈ 0.2 ± 0.03 s.
                Rng plan_rng(trial.seed, "bench-plan");
                bench::RollPlan plan;
                plan.profile_velocity = speed;
                plan.speed_factor = 1.0 + plan_rng.normal(0.0, 0.01);
                plan.lead_in = 0.08 + plan_rng.normal(0.0, 0.015);
                plan.settle = 0.11 + plan_rng.normal(0.0, 0.02);
                const auto t0 = std::chrono::steady_clock::now();
                if (auto st = bench::record_roll(sensor, trial, plan, rec); !st) {
                    std::fprintf(stderr, "%s: %s\n", id.c_str(), st.error().describe().c_str());
                    return 1;
                }
                const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                sim_seconds += spent;
                frames += static_cast<long>(rec.time.size());
                kind_seconds[object[0] == 'C'] += spent;
                kind_frames[object[0] == 'C'] += static_cast<long>(rec.time.size());
                samples_per_speed[speed].add(static_cast<double>(rec.time.size()));

                const auto verdict = judge_trial(fx, rec.channels);
                if (!verdict) {
                    std::fprintf(stderr, "%s: %s\n", id.c_str(), verdict.error().describe().c_str());
                    return 1;
                }
                ++trials;
                ++total_per_object[object];
                const bool cylinder = object[0] == 'C';
                (cylinder ? cyl_total : poly_total)++;
                if (all_above_threshold(*verdict, fx.settings())) ++all_above;
                if (verdict->clean) {
                    ++clean;
                    ++clean_per_object[object];
                    (cylinder ? cyl_clean : poly_clean)++;
                    if (cylinder)
                        ch13_interval[object][speed].add(
                            (static_cast<double>(verdict->channels[2].peak.max_index) -
                             static_cast<double>(verdict->channels[0].peak.max_index)) /
                            31.1);
                    amplitude[object].add(verdict->channels[1].amplitude);
                } else {
                    if (verdict->reason.find("low_amplitude") != std::string::npos) ++rejected_low_amplitude;
                    // Count the first channel's reason kind.
                    for (const char* kind : {"incomplete_start", "incomplete_end", "low_amplitude", "zero_width"})
                        if (verdict->reason.find(kind) != std::string::npos) ++reasons[kind];
                }
                std::vector<std::string> row{id, object, std::to_string(speed), std::to_string(rep),
                                             verdict->clean ? "1" : "0", verdict->reason};
                for (double f : verdict->values) row.push_back(std::isfinite(f) ? csv::format_number(f) : "");
                csv::append_row(features_csv, row);
            }
        }
    }

    std::printf("sim calibration: %d trials (%d runs x 9 objects x 3 speeds), run seed %llu\n\n", trials, opt.runs,
                static_cast<unsigned long long>(opt.seed));
    std::printf("%-44s %-26s %s\n", "observable", "simulation", "paper");
    const char* paper_samples[] = {"205 +- 5", "140 +- 3", "106 +- 2"};
    for (std::size_t i = 0; i < speeds.size(); ++i) {
        const auto& s = samples_per_speed[speeds[i]];
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.1f +- %.1f [%g..%g]", s.mean(), s.sd(), s.min(), s.max());
        std::printf("samples per trial, speed %-2d                  %-26s %s\n", speeds[i], buf, paper_samples[i]);
    }
    char buf[96];
    std::snprintf(buf, sizeof buf, "%d/%d = %.1f %%", clean, trials, 100.0 * clean / trials);
    std::printf("%-44s %-26s %s\n", "clean trials overall", buf, "1164/1350 = 86.2 %");
    std::snprintf(buf, sizeof buf, "%d/%d", cyl_clean, cyl_total);
    std::printf("%-44s %-26s %s\n", "clean cylinder trials", buf, "450/450");
    std::snprintf(buf, sizeof buf, "%d/%d = %.1f %%", poly_clean, poly_total, 100.0 * poly_clean / poly_total);
    std::printf("%-44s %-26s %s\n", "clean polygon trials", buf, "714/900 = 79.3 %");
    std::snprintf(buf, sizeof buf, "%d/%d", all_above, trials);
    std::printf("%-44s %-26s %s\n", "trials with every channel max > 0.01", buf, "1350/1350");
    std::snprintf(buf, sizeof buf, "%d", rejected_low_amplitude);
    std::printf("%-44s %-26s %s\n", "rejections for a low peak (missing contact)", buf, "0");
    std::printf("rejection kinds (a trial may have several):");
    for (const auto& [k, n] : reasons) std::printf(" %s=%d", k.c_str(), n);
    std::printf("\nclean per object:");
    for (const auto& o : objects) std::printf(" %s %d/%d", o.c_str(), clean_per_object[o], total_per_object[o]);
    std::printf("\nch2 amplitude (clean trials, mean +- sd):");
    for (const auto& o : objects) std::printf(" %s %.3f+-%.3f", o.c_str(), amplitude[o].mean(), amplitude[o].sd());
    std::printf("\n");

    // Noise after smoothing. The paper's ±0.005 is the noise left on a trial after
    // the smoothing that trial gets; an empty-hand recording on its own gets a
    // window of 1-2 (white noise has no dominant low frequency), so each empty-hand
    // recording is smoothed with the windows a contact trial of the same speed
    // received (the objects in turn). Per channel over every sample of
    // --noise-trials recordings: sd, 99th percentile and maximum of |y|.
    {
        const int per_speed = (opt.noise_trials + 2) / 3;
        std::array<std::vector<double>, 3> magnitude;
        std::array<std::vector<double>, 3> window_used;
        double worst_own = 0.0;
        for (int speed : speeds) {
            for (int rep = 0; rep < per_speed; ++rep) {
                bench::RollPlan plan;
                plan.profile_velocity = speed;
                const std::string& object = objects[static_cast<std::size_t>(rep) % objects.size()];
                TrialInfo contact{"window", object, std::to_string(speed), rep, mix64(opt.seed + 991 + rep), {}};
                if (auto st = bench::record_roll(sensor, contact, plan, rec); !st) return 1;
                std::array<int, 3> windows{};
                const double factor = fx.settings().smoothing_factor;
                for (std::size_t c = 0; c < 3; ++c) {
                    windows[c] = features::smoothing_window(rec.channels[c], factor);
                    window_used[c].push_back(windows[c]);
                }
                TrialInfo t{"noise", "", std::to_string(speed), rep, mix64(opt.seed + 77 + rep), {}};
                if (auto st = bench::record_roll(sensor, t, plan, rec); !st) return 1;
                for (std::size_t c = 0; c < 3; ++c) {
                    const int own = features::smoothing_window(rec.channels[c], factor);
                    for (double v : features::gaussian_smooth(rec.channels[c], own))
                        worst_own = std::max(worst_own, std::abs(v));
                    for (double v : features::gaussian_smooth(rec.channels[c], windows[c]))
                        magnitude[c].push_back(std::abs(v));
                }
            }
        }
        std::printf("noise after smoothing: %d empty-hand recordings, each smoothed with the windows of a contact "
                    "trial at its speed (paper: typically within +-0.005; a peak must pass 0.01)\n",
                    3 * per_speed);
        for (std::size_t c = 0; c < 3; ++c) {
            auto& m = magnitude[c];
            double sum2 = 0.0;
            for (double v : m) sum2 += v * v;
            const double sd = std::sqrt(sum2 / static_cast<double>(m.size()));  // about 0: the noise's own mean is 0
            auto& w = window_used[c];
            std::nth_element(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(w.size() / 2), w.end());
            const double median_window = w[w.size() / 2];
            const double min_window = *std::min_element(w.begin(), w.end());
            const double max = *std::max_element(m.begin(), m.end());
            const auto at99 = m.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(m.size() - 1));
            std::nth_element(m.begin(), at99, m.end());
            std::printf("  ch%zu: sd %.4f, p99 |y| %.4f, max |y| %.4f over %zu samples (window median %g, min %g)%s\n",
                        c + 1, sd, *at99, max, m.size(), median_window, min_window,
                        *at99 <= 0.005 && max < 0.01 ? "" : "  <-- outside the paper's bound (p99 <= 0.005, max < 0.01)");
        }
        std::snprintf(buf, sizeof buf, "max |y| %.4f", worst_own);
        std::printf("%-44s %-26s %s\n", "  (empty hand, its own window)", buf, "");
    }
    std::printf("\ncylinders: ch1 -> ch3 maximum interval, s (bigger cylinders must be faster)\n");
    for (int speed : speeds) {
        std::printf("  speed %-2d:", speed);
        for (const auto& o : {"C1", "C2", "C3"}) {
            const auto& s = ch13_interval[o][speed];
            std::printf("  %s %.3f +- %.3f", o, s.mean(), s.sd());
        }
        std::printf("\n");
    }
    // Cost: the stock experiment's recordings alone (no feature extraction),
    // best of three passes so that other work on a shared machine counts less.
    // Process CPU time is reported beside wall time: on a shared, loaded machine
    // wall time mostly measures the other processes.
    double best = 1e300, best_cpu = 1e300;
    long best_frames = 0;
    for (int pass = 0; pass < 3; ++pass) {
        long n = 0;
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        for (const auto& object : objects)
            for (int speed : speeds)
                for (int rep = 1; rep <= opt.runs; ++rep) {
                    const std::string id = object + "-s" + std::to_string(speed) + "-r" + std::to_string(rep);
                    TrialInfo trial{id, object, std::to_string(speed), rep, mix64(opt.seed ^ label_hash(id)), {}};
                    bench::RollPlan plan;
                    plan.profile_velocity = speed;
                    if (auto st = bench::record_roll(sensor, trial, plan, rec); !st) return 1;
                    n += static_cast<long>(rec.time.size());
                }
        const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
        best = std::min(best, spent);
        best_cpu = std::min(best_cpu, cpu);
        best_frames = n;
    }
    std::printf("\ncost of the %d recordings (best of 3 passes, one thread, %ld frames): CPU %.3f s = %.2f us per frame;"
                " wall %.3f s = %.2f us per frame\n",
                trials, best_frames, best_cpu, 1e6 * best_cpu / best_frames, best, 1e6 * best / best_frames);
    std::printf("first pass, by kind (%.3f s for %ld frames = %.2f us per frame; plugin class, record loop included)\n",
                sim_seconds, frames, 1e6 * sim_seconds / frames);
    std::printf("      cylinders %.2f us per frame, polygons %.2f us per frame\n",
                1e6 * kind_seconds[true] / std::max(1L, kind_frames[true]),
                1e6 * kind_seconds[false] / std::max(1L, kind_frames[false]));

    if (!opt.features.empty()) {
        std::ofstream out(opt.features);
        out << features_csv;
        std::printf("features written to %s\n", opt.features.c_str());
    }
    return 0;
}
