#include "rollsense/bagged_trees/ensemble.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include "tree_builder.hpp"

namespace rollsense::bagged_trees {

Status Ensemble::train(const FeatureTable& data, const EnsembleOptions& options) {
    const std::size_t n = data.rows, p = data.cols(), k = data.class_names.size();
    if (n == 0) return {ErrorCode::invalid_argument, "bagged_trees: cannot train on an empty feature table"};
    if (p == 0) return {ErrorCode::invalid_argument, "bagged_trees: the feature table has no feature columns"};
    if (k == 0) return {ErrorCode::invalid_argument, "bagged_trees: the feature table names no classes"};
    if (data.x.size() != n * p || data.y.size() != n)
        return {ErrorCode::invalid_argument, "bagged_trees: feature table holds " + std::to_string(data.x.size()) +
                                                 " values and " + std::to_string(data.y.size()) + " labels for " +
                                                 std::to_string(n) + " rows of " + std::to_string(p) + " features"};
    for (std::size_t r = 0; r < n; ++r) {
        if (data.y[r] < 0 || static_cast<std::size_t>(data.y[r]) >= k)
            return {ErrorCode::invalid_argument,
                    "bagged_trees: row " + std::to_string(r) + " has label " + std::to_string(data.y[r]) +
                        " outside the " + std::to_string(k) + " classes"};
        for (std::size_t f = 0; f < p; ++f)
            if (!std::isfinite(data.x[r * p + f]))
                return {ErrorCode::invalid_argument, "bagged_trees: row " + std::to_string(r) + " feature '" +
                                                         data.feature_names[f] +
                                                         "' is not a finite number (rejected trials must be "
                                                         "left out of training)"};
    }
    if (options.learners < 1)
        return {ErrorCode::invalid_argument, "bagged_trees: learners must be at least 1"};

    const TrainingSet set = make_training_set(data.x, data.y, n, p, k);
    std::vector<Tree> trees(static_cast<std::size_t>(options.learners));
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto work = [&] {
        try {
            TreeBuilder builder(set);
            std::vector<std::uint32_t> weights(n);
            for (;;) {
                const std::size_t b = next.fetch_add(1);
                if (b >= trees.size()) return;
                // Tree b's generator depends only on (seed, b): same model for any thread count.
                auto rng = random::Xoshiro256ss::numbered_stream(options.seed, b);
                std::fill(weights.begin(), weights.end(), 0u);
                for (std::size_t i = 0; i < n; ++i) ++weights[rng.below(n)];
                trees[b] = builder.build(weights, options.tree, rng);
            }
        } catch (...) {
            std::lock_guard lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            next = trees.size();
        }
    };
    unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    threads = std::min<unsigned>(threads, static_cast<unsigned>(trees.size()));
    if (threads <= 1) {
        work();
    } else {
        // The calling thread is one of the workers: a fit starts one thread
        // fewer (about 20 us of CPU each here, paid on every fold of a
        // cross-validation) and does not sit idle while the trees grow.
        std::vector<std::thread> pool;
        for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
        work();
        for (auto& t : pool) t.join();
    }
    if (failure) {
        try {
            std::rethrow_exception(failure);
        } catch (const std::exception& e) {
            return {ErrorCode::plugin_error, std::string("bagged_trees: training failed: ") + e.what()};
        }
    }
    trees_ = std::move(trees);
    class_names_ = data.class_names;
    feature_names_ = data.feature_names;
    options_ = options;
    return {};
}

int Ensemble::predict(std::span<const double> x, std::span<double> scores) const {
    const std::size_t k = classes();
    std::fill(scores.begin(), scores.end(), 0.0);
    for (const auto& t : trees_) {
        const double* leaf = t.leaf(x, k);
        for (std::size_t c = 0; c < k; ++c) scores[c] += leaf[c];
    }
    const double inv = 1.0 / static_cast<double>(trees_.size());
    int best = 0;
    for (std::size_t c = 0; c < k; ++c) {
        scores[c] *= inv;
        if (scores[c] > scores[static_cast<std::size_t>(best)]) best = static_cast<int>(c);
    }
    return best;
}

std::vector<int> Ensemble::predict_rows(std::span<const double> x, std::size_t rows) const {
    std::vector<int> out(rows);
    std::vector<double> scores(classes());
    const std::size_t p = predictors();
    for (std::size_t r = 0; r < rows; ++r) out[r] = predict(x.subspan(r * p, p), scores);
    return out;
}

}  // namespace rollsense::bagged_trees
