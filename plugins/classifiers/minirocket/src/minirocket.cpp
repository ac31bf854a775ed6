#include "rollsense/minirocket/minirocket.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "rollsense/atomic_file.hpp"
#include "rollsense/minirocket/parallel.hpp"
#include "rollsense/minirocket/ridge.hpp"

namespace rollsense::minirocket {

ParamSchema minirocket_schema() {
    const Options d;
    return {
        param_int("num_features", d.transform.num_features,
                  "MiniRocket features (rounded down to a multiple of 84; the paper's default ~10,000)", 84, 1000000),
        param_int("max_dilations_per_kernel", d.transform.max_dilations_per_kernel,
                  "at most this many dilations per kernel, spread exponentially over the series length", 1, 1024),
        param_number("alpha_log10_low", d.log10_alpha_low, "ridge α grid: log10 of the smallest α", -12, 12),
        param_number("alpha_log10_high", d.log10_alpha_high, "ridge α grid: log10 of the largest α", -12, 12),
        param_int("alphas", d.alphas, "ridge α grid: number of log-spaced values, chosen by leave-one-out", 1, 1000),
        param_int("seed", static_cast<std::int64_t>(d.transform.seed),
                  "seed of the channel subsets and the training series biases are drawn from", 0),
        param_int("threads", static_cast<std::int64_t>(d.threads),
                  "threads for the transform and the Gram matrix, 0 = all cores (the model does not depend on it)",
                  0, 1024),
    };
}

Result<Options> options_from(const ParamSet& p) {
    try {
        Options o;
        if (p.has("num_features")) o.transform.num_features = static_cast<int>(p.get_int("num_features"));
        if (p.has("max_dilations_per_kernel"))
            o.transform.max_dilations_per_kernel = static_cast<int>(p.get_int("max_dilations_per_kernel"));
        if (p.has("alpha_log10_low")) o.log10_alpha_low = p.get_number("alpha_log10_low");
        if (p.has("alpha_log10_high")) o.log10_alpha_high = p.get_number("alpha_log10_high");
        if (p.has("alphas")) o.alphas = static_cast<int>(p.get_int("alphas"));
        if (p.has("seed")) o.transform.seed = static_cast<std::uint64_t>(p.get_int("seed"));
        if (p.has("threads")) o.threads = static_cast<unsigned>(p.get_int("threads"));
        if (o.transform.num_features < kKernels)
            return Error{ErrorCode::invalid_argument, "minirocket: num_features must be at least 84 (one per kernel)"};
        if (o.transform.max_dilations_per_kernel < 1)
            return Error{ErrorCode::invalid_argument, "minirocket: max_dilations_per_kernel must be at least 1"};
        if (o.alphas < 1) return Error{ErrorCode::invalid_argument, "minirocket: alphas must be at least 1"};
        if (o.log10_alpha_low > o.log10_alpha_high)
            return Error{ErrorCode::invalid_argument,
                         "minirocket: alpha_log10_low is above alpha_log10_high; swap them"};
        return o;
    } catch (const StatusError& e) {
        return e.status();
    }
}

Status MiniRocket::on_configure(const ParamSet& params, const PluginContext&) {
    auto o = options_from(params);
    if (!o) return o.status();
    options_ = *o;
    return {};
}

namespace {
std::vector<float> to_float(std::span<const double> v) {
    std::vector<float> out(v.size());
    std::transform(v.begin(), v.end(), out.begin(), [](double d) { return static_cast<float>(d); });
    return out;
}
}  // namespace

Status MiniRocket::train(const FeatureTable& data) {
    if (data.series_length == 0)
        return Error{ErrorCode::invalid_argument,
                     "minirocket: takes prepared series (a table with series_length > 0), got a table of " +
                         std::to_string(data.feature_names.size()) +
                         " features; prepare the trials' series or use a feature classifier such as bagged_trees"};
    const std::size_t width = data.cols(), n = data.rows;
    if (data.x.size() != n * width)
        return Error{ErrorCode::invalid_argument, "minirocket: the table holds " + std::to_string(data.x.size()) +
                                                      " samples for " + std::to_string(n) + " rows of " +
                                                      std::to_string(width)};
    if (data.y.size() != n)
        return Error{ErrorCode::invalid_argument, "minirocket: " + std::to_string(data.y.size()) + " labels for " +
                                                      std::to_string(n) + " rows"};
    const int k = static_cast<int>(data.class_names.size());
    if (k < 2) return Error{ErrorCode::invalid_argument, "minirocket: needs at least 2 classes"};
    for (std::size_t i = 0; i < n; ++i) {
        if (data.y[i] < 0 || data.y[i] >= k)
            return Error{ErrorCode::invalid_argument, "minirocket: row " + std::to_string(i) + " has label " +
                                                          std::to_string(data.y[i]) + " outside the " +
                                                          std::to_string(k) + " classes"};
    }
    for (std::size_t i = 0; i < data.x.size(); ++i)
        if (!std::isfinite(data.x[i]))
            return Error{ErrorCode::invalid_argument,
                         "minirocket: row " + std::to_string(i / width) + " channel '" +
                             data.channel_names[(i % width) / data.series_length] + "' sample " +
                             std::to_string(i % data.series_length) + " is not a finite number"};

    const unsigned threads = resolve_threads(options_.threads);
    const auto series = to_float(data.x);
    Model m;
    m.class_names = data.class_names;
    m.channel_names = data.channel_names;
    m.series_rule = data.series_rule;
    if (auto s = m.transform.fit(series, n, data.channel_names.size(), data.series_length, options_.transform); !s)
        return s;
    const std::size_t p = m.transform.features();
    RowMatrixF x(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(p));
    m.transform.transform(series, n, {x.data(), n * p}, threads);

    // Standardise with the training statistics (constant features keep scale 1).
    m.mean.resize(p);
    m.scale.resize(p);
    // Row by row in double (the matrix is row-major; column walks would stride).
    std::vector<double> sum(p, 0.0), sq(p, 0.0);
    for (std::size_t r = 0; r < n; ++r) {
        const float* v = x.data() + r * p;
        for (std::size_t j = 0; j < p; ++j) {
            sum[j] += v[j];
            sq[j] += static_cast<double>(v[j]) * v[j];
        }
    }
    for (std::size_t j = 0; j < p; ++j) {
        const double mu = sum[j] / static_cast<double>(n);
        const double var = std::max(0.0, sq[j] / static_cast<double>(n) - mu * mu);
        m.mean[j] = static_cast<float>(mu);
        m.scale[j] = var > 1e-12 ? static_cast<float>(std::sqrt(var)) : 1.0f;
    }
    for (std::size_t r = 0; r < n; ++r) {
        float* v = x.data() + r * p;
        for (std::size_t j = 0; j < p; ++j) v[j] = (v[j] - m.mean[j]) / m.scale[j];
    }

    auto fit = fit_ridge_loo(x, data.y, k, log_grid(options_.log10_alpha_low, options_.log10_alpha_high, options_.alphas),
                             threads);
    if (!fit) return fit.status();
    m.weights.resize(p * static_cast<std::size_t>(k));
    for (std::size_t j = 0; j < p; ++j)
        for (int c = 0; c < k; ++c)
            m.weights[j * static_cast<std::size_t>(k) + static_cast<std::size_t>(c)] =
                static_cast<float>(fit->weights(static_cast<Eigen::Index>(j), c));
    m.intercept.assign(fit->intercept.data(), fit->intercept.data() + k);
    m.alpha = fit->alpha;
    m.loo_error = fit->loo_error;
    model_ = std::move(m);
    return {};
}

Status MiniRocket::check_row_width(std::size_t width) const {
    if (!model_.trained()) return Error{ErrorCode::state_error, "minirocket: predict before train or load"};
    if (width != model_.row_width())
        return Error{ErrorCode::invalid_argument,
                     "minirocket: got a row of " + std::to_string(width) + " samples, the model takes " +
                         std::to_string(model_.transform.channels()) + " channels × " +
                         std::to_string(model_.transform.length()) + " samples = " +
                         std::to_string(model_.row_width()) + "; prepare the series as for training"};
    return {};
}

Prediction MiniRocket::decide(const float* f) const {
    const std::size_t k = model_.classes(), p = model_.transform.features();
    std::vector<double> d(model_.intercept);
    for (std::size_t j = 0; j < p; ++j) {
        const double z = (static_cast<double>(f[j]) - model_.mean[j]) / model_.scale[j];
        const float* w = model_.weights.data() + j * k;
        for (std::size_t c = 0; c < k; ++c) d[c] += z * w[c];
    }
    Prediction out;
    out.label = static_cast<int>(std::max_element(d.begin(), d.end()) - d.begin());
    out.class_name = model_.class_names[static_cast<std::size_t>(out.label)];
    const double top = d[static_cast<std::size_t>(out.label)];
    double sum = 0.0;
    out.scores.resize(k);
    for (std::size_t c = 0; c < k; ++c) sum += out.scores[c] = std::exp(d[c] - top);
    for (auto& s : out.scores) s /= sum;
    return out;
}

Result<Prediction> MiniRocket::predict(std::span<const double> row) const {
    auto many = predict_many(row, 1);
    if (!many) return many.error();
    return std::move(many->front());
}

Result<std::vector<Prediction>> MiniRocket::predict_many(std::span<const double> rows, std::size_t count) const {
    if (!model_.trained()) return Error{ErrorCode::state_error, "minirocket: predict before train or load"};
    if (count == 0 || rows.size() % count != 0)
        return Error{ErrorCode::invalid_argument, "minirocket: " + std::to_string(rows.size()) +
                                                      " samples do not split into " + std::to_string(count) + " rows"};
    if (auto s = check_row_width(rows.size() / count); !s) return s.error();
    const std::size_t width = model_.row_width();
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (!std::isfinite(rows[i]))
            return Error{ErrorCode::invalid_argument,
                         "minirocket: row " + std::to_string(i / width) + " channel '" +
                             model_.channel_names[(i % width) / model_.transform.length()] + "' sample " +
                             std::to_string(i % model_.transform.length()) + " is not a finite number"};
    const auto series = to_float(rows);
    const std::size_t p = model_.transform.features();
    std::vector<float> features(count * p);
    // One row is ~0.2 ms of work: threads would cost more than they save.
    model_.transform.transform(series, count, features, count > 1 ? resolve_threads(options_.threads) : 1);
    std::vector<Prediction> out;
    out.reserve(count);
    for (std::size_t r = 0; r < count; ++r) out.push_back(decide(features.data() + r * p));
    return out;
}

Status MiniRocket::save(const std::filesystem::path& file) const {
    if (!model_.trained())
        return {ErrorCode::state_error,
                "minirocket: nothing to save to '" + file.string() + "': the model is not trained"};
    for (const auto* names : {&model_.class_names, &model_.channel_names})
        for (const auto& n : *names)
            if (n.find_first_of("\r\n") != std::string::npos)
                return {ErrorCode::invalid_argument, "minirocket: name '" + n + "' contains a line break"};
    if (model_.series_rule.find_first_of("\r\n") != std::string::npos)
        return {ErrorCode::invalid_argument, "minirocket: the series rule '" + model_.series_rule +
                                                 "' contains a line break; the model file keeps it on one line"};
    return write_file_atomic(file, model_.serialize(options_));
}

Status MiniRocket::load(const std::filesystem::path& file) {
    // Far above any model (P x K weights), far below what would exhaust a
    // machine reading it whole.
    constexpr std::uintmax_t kMaxModelBytes = std::uintmax_t{1} << 30;
    std::error_code ec;
    if (const auto size = std::filesystem::file_size(file, ec); !ec && size > kMaxModelBytes)
        return {ErrorCode::parse_error, "model file '" + file.string() + "' is " + std::to_string(size >> 20) +
                                            " MiB, more than any MiniRocket model (limit " +
                                            std::to_string(kMaxModelBytes >> 20) + " MiB): not a model file?"};
    std::ifstream in(file, std::ios::binary);
    if (!in)
        return {ErrorCode::not_found, "model file '" + file.string() +
                                          "' cannot be opened (does it exist? train one with 'rollsense train')"};
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) return {ErrorCode::io_error, "model file '" + file.string() + "' could not be read"};
    Model loaded;
    Options options = options_;
    // deserialize() checks every count before allocating; this only keeps a
    // machine out of memory from escaping the Status API as an exception.
    try {
        if (auto s = loaded.deserialize(ss.str(), file.string(), options); !s) return s;
    } catch (const std::exception& e) {
        return {ErrorCode::io_error, "model file '" + file.string() + "' could not be loaded: " + e.what()};
    }
    model_ = std::move(loaded);
    options_ = options;
    return {};
}

Result<ValueMap> MiniRocket::invoke(const std::string& verb, const ValueMap& args) {
    if (verb != "info") return Classifier::invoke(verb, args);
    ValueMap out;
    out["trained"] = model_.trained();
    out["features"] = static_cast<std::int64_t>(model_.transform.features());
    std::vector<std::int64_t> dil(model_.transform.dilations().begin(), model_.transform.dilations().end());
    out["dilations"] = dil;
    out["alpha"] = model_.alpha;
    out["classes"] = model_.class_names;
    out["channels"] = model_.channel_names;
    out["series_length"] = static_cast<std::int64_t>(model_.transform.length());
    out["series_rule"] = model_.series_rule;
    return out;
}

}  // namespace rollsense::minirocket
