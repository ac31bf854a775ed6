#include "analysis/learn/bayes_opt.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "analysis/learn/gaussian_process.hpp"
#include "analysis/learn/random.hpp"

namespace rollsense::learn {

using Scale = SearchDimension::Scale;

Result<SearchSpace> declared_search_space(const ClassifierFactory& factory, const ParamSet& params, std::size_t rows,
                                          std::size_t cols, const SearchSpace& given) {
    if (!given.empty()) return given;
    // One untrained instance: the space is the plugin's to declare, and its
    // ranges may depend on the configured parameters as well as the shape.
    auto probe = factory(params);
    if (!probe) return Status(probe.error()).with_context("asking the classifier for its search space");
    try {  // a checked plugin throws its refused space (checked_classifier): a Status here, not a C++ exception in Lua
        return (*probe)->search_space(rows, cols);
    } catch (const StatusError& e) {
        return e.status();
    }
}

Result<SearchSpace> tuning_space(const ClassifierFactory& factory, const ParamSet& params, std::size_t rows,
                                 std::size_t cols, const SearchSpace& given, const std::string& classifier) {
    auto space = declared_search_space(factory, params, rows, cols, given);
    if (!space) return space;
    if (space->empty())
        return Error{ErrorCode::invalid_argument,
                     "classifier '" + (classifier.empty() ? std::string("(unnamed)") : classifier) +
                         "' declares no hyperparameters to tune (its search_space is empty); run without "
                         "--optimize / optimize=true and set its parameters with --set KEY=VALUE, or choose a "
                         "classifier that declares a search space"};
    return space;
}

namespace {

// A point of the search space: one value per dimension (a number, or the
// index of a categorical choice).
using Point = std::vector<double>;

bool integer_scale(Scale s) { return s == Scale::integer_log || s == Scale::integer_linear; }
bool log_scale(Scale s) { return s == Scale::integer_log || s == Scale::real_log; }

double from_unit(const SearchDimension& d, double u) {
    u = std::clamp(u, 0.0, 1.0);
    double v = log_scale(d.scale) ? std::exp(std::log(d.low) + u * (std::log(d.high) - std::log(d.low)))
                                  : d.low + u * (d.high - d.low);
    if (integer_scale(d.scale)) v = std::round(v);
    return std::clamp(v, d.low, d.high);
}

double to_unit(const SearchDimension& d, double v) {
    if (d.high <= d.low) return 0.0;
    return log_scale(d.scale) ? (std::log(v) - std::log(d.low)) / (std::log(d.high) - std::log(d.low))
                              : (v - d.low) / (d.high - d.low);
}

std::size_t encoded_size(const SearchSpace& space) {
    std::size_t n = 0;
    for (const auto& d : space) n += d.scale == Scale::categorical ? d.choices.size() : 1;
    return n;
}

// Unit-cube encoding for the GP; a categorical becomes a one-hot block, so
// two different choices are equally far apart.
Eigen::VectorXd encode(const SearchSpace& space, const Point& p) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(encoded_size(space)));
    Eigen::Index at = 0;
    for (std::size_t i = 0; i < space.size(); ++i) {
        const auto& d = space[i];
        if (d.scale == Scale::categorical) {
            e(at + static_cast<Eigen::Index>(p[i])) = 1.0;
            at += static_cast<Eigen::Index>(d.choices.size());
        } else {
            e(at++) = to_unit(d, p[i]);
        }
    }
    return e;
}

Point random_point(const SearchSpace& space, SplitMix& rng) {
    Point p(space.size());
    for (std::size_t i = 0; i < space.size(); ++i) {
        const auto& d = space[i];
        p[i] = d.scale == Scale::categorical ? static_cast<double>(rng.below(d.choices.size()))
                                             : from_unit(d, rng.uniform());
    }
    return p;
}

double normal_draw(SplitMix& rng) {
    const double u1 = std::max(rng.uniform(), 1e-300), u2 = rng.uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

// A neighbour of p: each numeric coordinate moved by N(0, 0.1) in unit space,
// each categorical switched with probability 0.2.
Point perturb(const SearchSpace& space, const Point& p, SplitMix& rng) {
    Point q = p;
    for (std::size_t i = 0; i < space.size(); ++i) {
        const auto& d = space[i];
        if (d.scale == Scale::categorical) {
            if (rng.uniform() < 0.2) q[i] = static_cast<double>(rng.below(d.choices.size()));
        } else {
            q[i] = from_unit(d, to_unit(d, p[i]) + 0.1 * normal_draw(rng));
        }
    }
    return q;
}

ParamSet to_params(const SearchSpace& space, const Point& p, const ParamSet& fixed) {
    ParamSet s = fixed;
    for (std::size_t i = 0; i < space.size(); ++i) {
        const auto& d = space[i];
        if (d.scale == Scale::categorical) s.set(d.name, d.choices[static_cast<std::size_t>(p[i])]);
        else if (integer_scale(d.scale)) s.set(d.name, static_cast<std::int64_t>(p[i]));
        else s.set(d.name, p[i]);
    }
    return s;
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * 3.141592653589793); }

}  // namespace

Result<BayesOptResult> bayes_optimize(const SearchSpace& space, const Objective& objective, const ParamSet& fixed,
                                      const BayesOptOptions& options) {
    if (space.empty()) return Error{ErrorCode::invalid_argument, "bayes_optimize: empty search space"};
    for (const auto& d : space) {
        if (d.scale == Scale::categorical ? d.choices.empty() : !(d.high >= d.low))
            return Error{ErrorCode::invalid_argument, "bayes_optimize: dimension '" + d.name + "' has an empty range"};
        if (log_scale(d.scale) && d.low <= 0.0)
            return Error{ErrorCode::invalid_argument, "bayes_optimize: log-scaled '" + d.name + "' must be > 0"};
    }
    if (options.evaluations < 1) return Error{ErrorCode::invalid_argument, "bayes_optimize: no evaluations asked for"};

    SplitMix rng(options.seed);
    BayesOptResult result;
    std::vector<Point> visited;
    std::set<Point> seen;
    std::vector<double> values;
    auto evaluate = [&](const Point& p) -> Status {
        ParamSet params = to_params(space, p, fixed);
        auto v = objective(params);
        if (!v) return Status(v.error()).with_context("optimiser evaluation " + std::to_string(visited.size() + 1) +
                                                      " (" + describe_params(params, space) + ")");
        visited.push_back(p);
        seen.insert(p);
        values.push_back(*v);
        result.history.push_back({params, *v});
        if (options.progress) options.progress(static_cast<int>(visited.size()), params, *v);
        return {};
    };

    const int seeds = std::clamp(options.seed_points, 1, options.evaluations);
    for (int i = 0; i < seeds; ++i)
        if (auto s = evaluate(random_point(space, rng)); !s) return s;

    GaussianProcess gp;
    auto fit = [&] {
        Eigen::MatrixXd x(static_cast<Eigen::Index>(visited.size()), static_cast<Eigen::Index>(encoded_size(space)));
        Eigen::VectorXd y(static_cast<Eigen::Index>(visited.size()));
        for (std::size_t i = 0; i < visited.size(); ++i) {
            x.row(static_cast<Eigen::Index>(i)) = encode(space, visited[i]).transpose();
            y(static_cast<Eigen::Index>(i)) = values[i];
        }
        gp.fit(x, y);
    };

    while (static_cast<int>(visited.size()) < options.evaluations) {
        fit();
        const double best_seen = *std::min_element(values.begin(), values.end());
        // Candidates: uniform over the space, plus neighbours of the best five.
        std::vector<Point> candidates;
        for (int i = 0; i < options.candidates; ++i) candidates.push_back(random_point(space, rng));
        std::vector<std::size_t> order(visited.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](auto a, auto b) { return values[a] < values[b]; });
        for (std::size_t j = 0; j < std::min<std::size_t>(5, order.size()); ++j)
            for (int i = 0; i < 100; ++i) candidates.push_back(perturb(space, visited[order[j]], rng));

        double best_ei = -1.0;
        const Point* pick = nullptr;
        for (const auto& c : candidates) {
            if (seen.count(c)) continue;  // a deterministic objective gains nothing from a repeat
            double mu = 0, sd = 0;
            gp.predict(encode(space, c), mu, sd);
            const double margin = options.exploration * std::max(1e-12, sd);
            const double improve = best_seen - mu - margin;
            const double z = improve / sd;
            const double ei = improve * normal_cdf(z) + sd * normal_pdf(z);
            if (ei > best_ei) {
                best_ei = ei;
                pick = &c;
            }
        }
        const Point next = pick ? *pick : random_point(space, rng);
        if (auto s = evaluate(next); !s) return s;
    }

    // The visited point whose modelled objective has the lowest upper bound.
    fit();
    double best_ucb = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < visited.size(); ++i) {
        double mu = 0, sd = 0;
        gp.predict(encode(space, visited[i]), mu, sd);
        if (mu + 1.96 * sd < best_ucb) {
            best_ucb = mu + 1.96 * sd;
            result.best = i;
            result.best_predicted = mu;
        }
    }
    return result;
}

namespace {
// "name=value"; a string as it is (format_param_value quotes it).
std::string describe_value(const std::string& name, const ParamValue& v) {
    const auto* s = std::get_if<std::string>(&v);
    return name + "=" + (s ? *s : format_param_value(v));
}
}  // namespace

std::string describe_params(const ParamSet& params, const SearchSpace& space) {
    std::string out;
    for (const auto& d : space)
        if (params.has(d.name)) out += (out.empty() ? "" : " ") + describe_value(d.name, params.values().at(d.name));
    return out;
}

std::string describe_param_values(const ParamSet& params) {
    std::string out;
    for (const auto& [name, v] : params.values()) out += (out.empty() ? "" : " ") + describe_value(name, v);
    return out;
}

}  // namespace rollsense::learn
