#include "rollsense/nearest_centroid/nearest_centroid.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "rollsense/atomic_file.hpp"

namespace rollsense::nearest_centroid {
namespace {

// A standard deviation this small against the mean is rounding noise of a
// constant column (a mean of identical values need not be exactly that value),
// not a spread worth dividing by.
bool negligible_spread(double sd, double mean) { return !(sd > 1e-12 * std::max(1.0, std::fabs(mean))); }

// sign(v) · max(|v| − shrink, 0)
double soft_threshold(double v, double shrink) {
    const double m = std::fabs(v) - shrink;
    return m > 0.0 ? std::copysign(m, v) : 0.0;
}

}  // namespace

ParamSchema nearest_centroid_schema() {
    const Options d;
    return {
        param_number("shrink", d.shrink,
                     "pull every standardised centroid coordinate this far towards the overall mean, stopping at it "
                     "(nearest shrunken centroid); 0 = plain nearest centroid",
                     0.0, 100.0, "sd"),
        param_number("temperature", d.temperature,
                     "softmax temperature of the scores (exp(-distance / temperature)); does not change the "
                     "predicted class",
                     1e-6, 1e6, "sd"),
    };
}

Status NearestCentroid::on_configure(const ParamSet& params, const PluginContext&) {
    try {
        Options o;
        if (params.has("shrink")) o.shrink = params.get_number("shrink");
        if (params.has("temperature")) o.temperature = params.get_number("temperature");
        if (!(o.shrink >= 0.0) || !std::isfinite(o.shrink))
            return {ErrorCode::invalid_argument, "nearest_centroid: shrink must be a finite number >= 0"};
        if (!(o.temperature > 0.0) || !std::isfinite(o.temperature))
            return {ErrorCode::invalid_argument, "nearest_centroid: temperature must be a finite number > 0"};
        options_ = o;
        return {};
    } catch (const StatusError& e) {
        return e.status();
    }
}

SearchSpace NearestCentroid::search_space(std::size_t, std::size_t) const {
    return {{"shrink", SearchDimension::Scale::real_linear, 0.0, 2.0, {}}};
}

Status NearestCentroid::train(const FeatureTable& data) {
    if (data.input() != ClassifierInput::features)
        return {ErrorCode::invalid_argument,
                "nearest_centroid takes feature vectors, not prepared series; extract features first"};
    const std::size_t n = data.rows, p = data.cols(), k = data.class_names.size();
    if (n == 0) return {ErrorCode::invalid_argument, "nearest_centroid: no training trials"};
    if (p == 0) return {ErrorCode::invalid_argument, "nearest_centroid: the table has no features"};
    if (k == 0) return {ErrorCode::invalid_argument, "nearest_centroid: the table names no classes"};
    if (data.x.size() != n * p || data.y.size() != n)
        return {ErrorCode::invalid_argument, "nearest_centroid: the table's sizes do not agree (" +
                                                 std::to_string(n) + " rows, " + std::to_string(p) + " features, " +
                                                 std::to_string(data.x.size()) + " values, " +
                                                 std::to_string(data.y.size()) + " labels)"};
    for (std::size_t r = 0; r < n; ++r) {
        if (data.y[r] < 0 || static_cast<std::size_t>(data.y[r]) >= k)
            return {ErrorCode::invalid_argument, "nearest_centroid: row " + std::to_string(r) + " has label " +
                                                     std::to_string(data.y[r]) + " outside the " +
                                                     std::to_string(k) + " classes"};
        for (std::size_t j = 0; j < p; ++j)
            if (!std::isfinite(data.x[r * p + j]))
                return {ErrorCode::invalid_argument, "nearest_centroid: row " + std::to_string(r) + " feature '" +
                                                         data.feature_names[j] + "' is not a finite number"};
    }

    Model m;
    m.class_names = data.class_names;
    m.feature_names = data.feature_names;
    m.options = options_;
    m.mean.assign(p, 0.0);
    m.sd.assign(p, 0.0);
    m.class_rows.assign(k, 0);
    for (std::size_t r = 0; r < n; ++r) {
        ++m.class_rows[static_cast<std::size_t>(data.y[r])];
        for (std::size_t j = 0; j < p; ++j) m.mean[j] += data.x[r * p + j];
    }
    for (double& v : m.mean) v /= static_cast<double>(n);
    for (std::size_t r = 0; r < n; ++r)
        for (std::size_t j = 0; j < p; ++j) {
            const double d = data.x[r * p + j] - m.mean[j];
            m.sd[j] += d * d;
        }
    // Sample standard deviation; one trial has no spread (every feature ignored).
    for (std::size_t j = 0; j < p; ++j) {
        m.sd[j] = n > 1 ? std::sqrt(m.sd[j] / static_cast<double>(n - 1)) : 0.0;
        if (negligible_spread(m.sd[j], m.mean[j])) m.sd[j] = 0.0;
    }

    m.centroids.assign(k * p, 0.0);
    for (std::size_t r = 0; r < n; ++r) {
        const auto c = static_cast<std::size_t>(data.y[r]);
        for (std::size_t j = 0; j < p; ++j)
            if (m.used(j)) m.centroids[c * p + j] += (data.x[r * p + j] - m.mean[j]) / m.sd[j];
    }
    for (std::size_t c = 0; c < k; ++c)
        for (std::size_t j = 0; j < p; ++j) {
            double& v = m.centroids[c * p + j];
            v = m.class_rows[c] ? soft_threshold(v / static_cast<double>(m.class_rows[c]), options_.shrink) : 0.0;
        }
    model_ = std::move(m);
    return {};
}

Result<Prediction> NearestCentroid::predict(std::span<const double> features) const {
    const Model& m = model_;
    if (!m.trained()) return Error{ErrorCode::state_error, "nearest_centroid: predict before train or load"};
    const std::size_t p = m.feature_names.size(), k = m.class_names.size();
    if (features.size() != p)
        return Error{ErrorCode::invalid_argument, "nearest_centroid: got " + std::to_string(features.size()) +
                                                      " features, the model was trained on " + std::to_string(p)};
    for (std::size_t j = 0; j < p; ++j)
        if (!std::isfinite(features[j]))
            return Error{ErrorCode::invalid_argument,
                         "nearest_centroid: feature '" + m.feature_names[j] + "' is not a finite number"};

    std::vector<double> z(p, 0.0);
    for (std::size_t j = 0; j < p; ++j)
        if (m.used(j)) z[j] = (features[j] - m.mean[j]) / m.sd[j];
    std::vector<double> dist(k, 0.0);
    Prediction out;
    double nearest = INFINITY;
    for (std::size_t c = 0; c < k; ++c) {
        if (!m.class_rows[c]) continue;
        double s = 0.0;
        for (std::size_t j = 0; j < p; ++j) {
            const double d = z[j] - m.centroids[c * p + j];
            s += d * d;
        }
        dist[c] = std::sqrt(s);
        if (dist[c] < nearest) {  // ties go to the first class
            nearest = dist[c];
            out.label = static_cast<int>(c);
        }
    }
    // Softmax of −distance / temperature, shifted by the nearest distance so
    // the largest term is exp(0) = 1 and nothing underflows to an all-zero sum.
    out.scores.assign(k, 0.0);
    double sum = 0.0;
    for (std::size_t c = 0; c < k; ++c)
        if (m.class_rows[c]) sum += out.scores[c] = std::exp(-(dist[c] - nearest) / m.options.temperature);
    for (double& s : out.scores) s /= sum;
    out.class_name = m.class_names[static_cast<std::size_t>(out.label)];
    return out;
}

Status NearestCentroid::save(const std::filesystem::path& file) const {
    if (!model_.trained())
        return {ErrorCode::state_error,
                "nearest_centroid: nothing to save to '" + file.string() + "': the model is not trained"};
    for (const auto* names : {&model_.class_names, &model_.feature_names})
        for (const auto& n : *names)
            if (n.find('\n') != std::string::npos || n.find('\r') != std::string::npos)
                return {ErrorCode::invalid_argument, "nearest_centroid: name '" + n + "' contains a line break"};
    return write_file_atomic(file, model_.serialize());
}

Status NearestCentroid::load(const std::filesystem::path& file) {
    // Far above any model (K x P numbers), far below what would exhaust a
    // machine reading it whole.
    constexpr std::uintmax_t kMaxModelBytes = std::uintmax_t{1} << 30;
    std::error_code ec;
    if (const auto size = std::filesystem::file_size(file, ec); !ec && size > kMaxModelBytes)
        return {ErrorCode::parse_error, "model file '" + file.string() + "' is " + std::to_string(size >> 20) +
                                            " MiB, more than any nearest_centroid model (limit " +
                                            std::to_string(kMaxModelBytes >> 20) + " MiB): not a model file?"};
    std::ifstream in(file, std::ios::binary);
    if (!in)
        return {ErrorCode::not_found, "model file '" + file.string() +
                                          "' cannot be opened (does it exist? train one with 'rollsense train "
                                          "DATASET --classifier nearest_centroid -o MODEL')"};
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) return {ErrorCode::io_error, "model file '" + file.string() + "' could not be read"};
    Model loaded;
    // deserialize() checks every count before allocating; this only keeps a
    // machine out of memory from escaping the Status API as an exception.
    try {
        if (auto s = loaded.deserialize(ss.str(), file.string()); !s) return s;
    } catch (const std::exception& e) {
        return {ErrorCode::io_error, "model file '" + file.string() + "' could not be loaded: " + e.what()};
    }
    model_ = std::move(loaded);
    options_ = model_.options;
    return {};
}

Result<ValueMap> NearestCentroid::invoke(const std::string& verb, const ValueMap& args) {
    if (verb != "info") return Classifier::invoke(verb, args);
    ValueMap out;
    std::vector<std::string> used, ignored;
    for (std::size_t j = 0; j < model_.feature_names.size(); ++j)
        (model_.used(j) ? used : ignored).push_back(model_.feature_names[j]);
    out["trained"] = model_.trained();
    out["classes"] = model_.class_names;
    out["features"] = used;
    out["ignored_features"] = ignored;
    out["shrink"] = options_.shrink;
    out["temperature"] = options_.temperature;
    return out;
}

}  // namespace rollsense::nearest_centroid
