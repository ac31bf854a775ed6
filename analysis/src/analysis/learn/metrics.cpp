#include "analysis/learn/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace rollsense::learn {

std::size_t ConfusionMatrix::total() const { return std::accumulate(counts.begin(), counts.end(), std::size_t{0}); }

std::size_t ConfusionMatrix::correct() const {
    std::size_t c = 0;
    for (std::size_t i = 0; i < size(); ++i) c += at(i, i);
    return c;
}

std::size_t ConfusionMatrix::row_total(std::size_t truth) const {
    std::size_t t = 0;
    for (std::size_t j = 0; j < size(); ++j) t += at(truth, j);
    return t;
}

double ConfusionMatrix::accuracy() const {
    const auto t = total();
    return t ? static_cast<double>(correct()) / static_cast<double>(t) : std::numeric_limits<double>::quiet_NaN();
}

std::vector<double> ConfusionMatrix::true_positive_rates() const {
    std::vector<double> out(size());
    for (std::size_t i = 0; i < size(); ++i) {
        const auto n = row_total(i);
        out[i] = n ? static_cast<double>(at(i, i)) / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
    }
    return out;
}

ConfusionMatrix confusion(std::span<const int> truth, std::span<const int> predicted,
                          const std::vector<std::string>& classes) {
    ConfusionMatrix m(classes);
    for (std::size_t i = 0; i < truth.size() && i < predicted.size(); ++i) m.add(truth[i], predicted[i]);
    return m;
}

Interval wilson_interval(std::size_t successes, std::size_t n, double z) {
    return wilson_interval_of_rate(n ? static_cast<double>(successes) / static_cast<double>(n) : 0.0, n, z);
}

Interval wilson_interval_of_rate(double p, std::size_t n, double z) {
    if (n == 0) return {0.0, 1.0};
    const double nn = static_cast<double>(n);
    const double z2 = z * z;
    const double centre = (p + z2 / (2 * nn)) / (1 + z2 / nn);
    const double half = z / (1 + z2 / nn) * std::sqrt(p * (1 - p) / nn + z2 / (4 * nn * nn));
    return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

double mean(std::span<const double> v) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double standard_deviation(std::span<const double> v) {
    if (v.size() < 2) return std::numeric_limits<double>::quiet_NaN();
    const double m = mean(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
}

PairedDifference paired_difference(std::span<const double> a, std::span<const double> b, double test_train_ratio) {
    PairedDifference d;
    const std::size_t n = std::min(a.size(), b.size());
    for (std::size_t i = 0; i < n; ++i) {
        const double diff = a[i] - b[i];
        d.per_fold.push_back(diff);
        if (diff > 0) ++d.a_better;
        else if (diff < 0) ++d.b_better;
        else ++d.ties;
    }
    if (n == 0) return d;
    d.mean = mean(d.per_fold);
    d.sd = standard_deviation(d.per_fold);
    const double nn = static_cast<double>(n);
    auto t_of = [&](double variance_factor) {
        if (d.mean == 0.0) return 0.0;
        const double se = std::sqrt(variance_factor) * d.sd;
        return se > 0.0 ? d.mean / se : std::copysign(std::numeric_limits<double>::infinity(), d.mean);
    };
    d.t = t_of(1.0 / nn);
    d.t_corrected = t_of(1.0 / nn + test_train_ratio);
    return d;
}

double Count::fraction() const {
    return n ? static_cast<double>(k) / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace rollsense::learn
