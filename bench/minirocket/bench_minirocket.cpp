// MiniRocket bench: our C++ plugin beside a numba/scikit-learn reference
// (minirocket_reference.py) on the same prepared series and the same folds.
//   bench_minirocket [--dataset DIR] [--length 128] [--repeats 10] [--folds 5]
//                    [--seed 1] [--threads 0] [--alpha-high 3] [--keep-amplitude] [--crop 0.1] [--no-python]
// (--alpha-high: log10 of the largest ridge α, for our side only;
// --keep-amplitude: the stand-in preparation skips the z-normalisation;
// --crop F: it crops where the channel sum exceeds F × its peak)
// Without --dataset: 1,170 synthetic shape trials × 3 channels × 128 samples
// (the size of the stock experiment). With --dataset: the clean trials of a
// recorded dataset, prepared by the bench's STAND-IN rule (prepare_series.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <string>

#include "prepare_series.hpp"
#include "rollsense/minirocket/minirocket.hpp"
#include "rollsense/minirocket/parallel.hpp"
#include "rollsense/random.hpp"

using namespace rollsense;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Stratified folds: per class, a seeded shuffle dealt round-robin.
std::vector<int> stratified_folds(const std::vector<int>& y, int k, std::uint64_t seed, int repeat) {
    auto rng = random::Xoshiro256ss::numbered_stream(seed, static_cast<std::uint64_t>(repeat));
    std::map<int, std::vector<std::size_t>> by_class;
    for (std::size_t i = 0; i < y.size(); ++i) by_class[y[i]].push_back(i);
    std::vector<int> fold(y.size());
    int next = 0;
    for (auto& [c, idx] : by_class) {
        for (std::size_t i = idx.size(); i > 1; --i) std::swap(idx[i - 1], idx[rng.below(i)]);
        for (std::size_t i = 0; i < idx.size(); ++i) fold[idx[i]] = (next++) % k;
    }
    return fold;
}

FeatureTable subset(const FeatureTable& t, const std::vector<std::size_t>& rows) {
    FeatureTable s = t;
    s.rows = rows.size();
    s.x.clear();
    s.y.clear();
    for (auto r : rows) {
        auto row = t.row(r);
        s.x.insert(s.x.end(), row.begin(), row.end());
        s.y.push_back(t.y[r]);
    }
    return s;
}

struct Stats {
    double mean = 0, sd = 0;
};
Stats stats(const std::vector<double>& v) {
    Stats s;
    for (double x : v) s.mean += x;
    s.mean /= static_cast<double>(v.size());
    for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
    s.sd = std::sqrt(s.sd / static_cast<double>(std::max<std::size_t>(1, v.size() - 1)));
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    std::string dataset, out_dir = "/tmp/bench-minirocket";
    std::size_t length = 128;
    int repeats = 10, folds = 5;
    std::uint64_t seed = 1;
    unsigned threads = 0;
    bool python = true, keep_amplitude = false;
    double alpha_high = 3.0, crop = 0.1;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::cerr << "bench_minirocket: " << a << " needs a value\n";
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--dataset") dataset = value();
        else if (a == "--out") out_dir = value();
        else if (a == "--length") length = std::stoul(value());
        else if (a == "--repeats") repeats = std::stoi(value());
        else if (a == "--folds") folds = std::stoi(value());
        else if (a == "--seed") seed = std::stoull(value());
        else if (a == "--threads") threads = static_cast<unsigned>(std::stoul(value()));
        else if (a == "--no-python") python = false;
        else if (a == "--alpha-high") alpha_high = std::stod(value());
        else if (a == "--keep-amplitude") keep_amplitude = true;
        else if (a == "--crop") crop = std::stod(value());
        else {
            std::cerr << "usage: bench_minirocket [--dataset DIR] [--out DIR] [--length 128] [--repeats 10] "
                         "[--folds 5] [--seed 1] [--threads 0] [--alpha-high 3] [--keep-amplitude] [--crop 0.1] [--no-python]\n";
            return 2;
        }
    }
    threads = minirocket::resolve_threads(threads);

    FeatureTable data;
    if (dataset.empty()) {
        data = bench::synthetic_shapes(390, length, seed);
        std::cout << "data: synthetic shapes, ";
    } else {
        std::size_t skipped = 0;
        auto d = bench::prepare_dataset(dataset, length, skipped, !keep_amplitude, crop);
        if (!d) {
            std::cerr << "bench_minirocket: " << d.error().message << "\n";
            return 1;
        }
        data = std::move(*d);
        std::cout << "data: " << dataset << " (clean trials; " << skipped
                  << " skipped), prepared by the bench's STAND-IN rule, ";
    }
    std::cout << data.rows << " trials × " << data.channel_names.size() << " channels × " << data.series_length
              << " samples, " << data.class_names.size() << " classes; " << threads << " threads\n";

    // Series, labels and folds for the reference.
    std::filesystem::create_directories(out_dir);
    {
        std::ofstream x(std::filesystem::path(out_dir) / "x.f64", std::ios::binary);
        x.write(reinterpret_cast<const char*>(data.x.data()), static_cast<std::streamsize>(data.x.size() * 8));
        std::ofstream meta(std::filesystem::path(out_dir) / "meta.txt");
        meta << data.rows << " " << data.channel_names.size() << " " << data.series_length << " "
             << data.class_names.size() << " " << repeats << " " << folds << "\n";
        for (int y : data.y) meta << y << " ";
        meta << "\n";
        for (int r = 0; r < repeats; ++r) {
            for (int f : stratified_folds(data.y, folds, seed, r)) meta << f << " ";
            meta << "\n";
        }
    }

    minirocket::Options options;
    options.threads = threads;
    options.transform.seed = seed;
    options.log10_alpha_high = alpha_high;

    // 1. Transform: fit biases on every trial and transform them all.
    const std::vector<float> xf(data.x.begin(), data.x.end());
    auto t0 = Clock::now();
    minirocket::Transform tr;
    if (auto s = tr.fit(xf, data.rows, data.channel_names.size(), data.series_length, options.transform); !s) {
        std::cerr << "bench_minirocket: " << s.error().message << "\n";
        return 1;
    }
    std::vector<float> feats(data.rows * tr.features());
    tr.transform(xf, data.rows, feats, threads);
    const double transform_s = seconds_since(t0);

    // 2. Repeated stratified k-fold evaluation through the Classifier interface.
    std::vector<double> acc;
    std::vector<double> alphas;
    t0 = Clock::now();
    for (int r = 0; r < repeats; ++r) {
        const auto fold = stratified_folds(data.y, folds, seed, r);
        for (int k = 0; k < folds; ++k) {
            std::vector<std::size_t> train_rows, test_rows;
            for (std::size_t i = 0; i < data.rows; ++i) (fold[i] == k ? test_rows : train_rows).push_back(i);
            const auto train = subset(data, train_rows), test = subset(data, test_rows);
            minirocket::MiniRocket m(options);
            if (auto s = m.train(train); !s) {
                std::cerr << "bench_minirocket: " << s.error().message << "\n";
                return 1;
            }
            auto p = m.predict_many(test.x, test.rows);
            if (!p) {
                std::cerr << "bench_minirocket: " << p.error().message << "\n";
                return 1;
            }
            std::size_t right = 0;
            for (std::size_t i = 0; i < test.rows; ++i) right += (*p)[i].label == test.y[i];
            acc.push_back(static_cast<double>(right) / static_cast<double>(test.rows));
            alphas.push_back(m.model().alpha);
        }
    }
    const double eval_s = seconds_since(t0);
    const Stats a = stats(acc);
    std::sort(alphas.begin(), alphas.end());

    // 3. One prediction (transform + ridge) of a model trained on every trial.
    minirocket::MiniRocket full(options);
    if (auto s = full.train(data); !s) {
        std::cerr << "bench_minirocket: " << s.error().message << "\n";
        return 1;
    }
    std::vector<double> one;
    for (int i = 0; i < 300; ++i) {
        t0 = Clock::now();
        auto p = full.predict(data.row(static_cast<std::size_t>(i) % data.rows));
        one.push_back(seconds_since(t0));
        if (!p) return 1;
    }
    std::sort(one.begin(), one.end());
    const double predict_s = one[one.size() / 2];

    std::printf("C++ minirocket: %zu features, accuracy %d × %d-fold %.2f %% ± %.2f, chosen α median %g\n",
                tr.features(), repeats, folds, 100 * a.mean, 100 * a.sd, alphas[alphas.size() / 2]);

    std::map<std::string, double> ref;
    if (python) {
        const std::string cmd = "NUMBA_NUM_THREADS=" + std::to_string(threads) +
                                " OPENBLAS_NUM_THREADS=" + std::to_string(threads) + " OMP_NUM_THREADS=" +
                                std::to_string(threads) + " /usr/bin/python3 " + ROLLSENSE_BENCH_DIR +
                                "/minirocket_reference.py " + out_dir + " " + std::to_string(seed);
        FILE* pipe = popen(cmd.c_str(), "r");
        if (pipe) {
            char line[512];
            while (std::fgets(line, sizeof line, pipe)) {
                std::istringstream ss(line);
                std::string key;
                double v = 0;
                if (ss >> key >> v) ref[key] = v;
            }
            if (pclose(pipe) != 0) std::cerr << "bench_minirocket: the reference failed (is python3-numba installed?)\n";
        }
        if (ref.count("accuracy_mean"))
            std::printf("numba reference: accuracy %.2f %% ± %.2f (JIT compile %.2f s, not counted)\n",
                        100 * ref["accuracy_mean"], 100 * ref["accuracy_sd"], ref["compile_s"]);
    }
    auto row = [&](const char* what, double ours, const char* key) {
        if (ref.count(key))
            std::printf("  %-34s C++ %9.4f s   numba %9.4f s   numba/C++ %6.2f×\n", what, ours, ref[key], ref[key] / ours);
        else
            std::printf("  %-34s C++ %9.4f s\n", what, ours);
    };
    row("transform (fit + all trials)", transform_s, "transform_s");
    row(("evaluation " + std::to_string(repeats) + " × " + std::to_string(folds) + "-fold").c_str(), eval_s, "evaluate_s");
    row("one prediction (median)", predict_s, "predict_s");
    return 0;
}
