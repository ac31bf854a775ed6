// Accuracy figures: confusion matrix, per-class true-positive rate, mean ± sd
// and the Wilson score interval for a pooled proportion.
#pragma once

#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace rollsense::learn {

struct ConfusionMatrix {
    std::vector<std::string> classes;
    std::vector<std::size_t> counts;  // row = true class, column = predicted class

    explicit ConfusionMatrix(std::vector<std::string> names = {})
        : classes(std::move(names)), counts(classes.size() * classes.size(), 0) {}
    std::size_t size() const { return classes.size(); }
    std::size_t at(std::size_t truth, std::size_t predicted) const { return counts[truth * size() + predicted]; }
    void add(int truth, int predicted) {
        ++counts[static_cast<std::size_t>(truth) * size() + static_cast<std::size_t>(predicted)];
    }
    std::size_t total() const;
    std::size_t correct() const;
    std::size_t row_total(std::size_t truth) const;
    double accuracy() const;
    // Recall per true class (NaN for a class without trials).
    std::vector<double> true_positive_rates() const;
};

ConfusionMatrix confusion(std::span<const int> truth, std::span<const int> predicted,
                          const std::vector<std::string>& classes);

struct Interval {
    double low = 0.0;
    double high = 0.0;
};

// Wilson score interval for `successes` of `n` (z = 1.96: 95 %).
Interval wilson_interval(std::size_t successes, std::size_t n, double z = 1.96);
// The same for an observed rate `p` over `n` independent cases (a rate pooled
// over repetitions of a CV that predicts the same n trials each time: the
// repetitions are not new cases, so n is the trials, not the predictions).
Interval wilson_interval_of_rate(double p, std::size_t n, double z = 1.96);

double mean(std::span<const double> v);
// Sample standard deviation (n − 1). Of fewer than two values it does not
// exist: NaN, which evaluation.json writes as null and every rendering shows
// as no_spread_text() instead of a "± sd" (one repetition has no spread).
double standard_deviation(std::span<const double> v);
inline bool has_spread(double sd) noexcept { return !std::isnan(sd); }
// What the text and the report say in place of "± sd" when !has_spread(sd).
inline constexpr const char* no_spread_text = "one repetition: no spread";

// Two classifiers scored on the same folds: the per-fold differences a − b and
// two paired t statistics on them (df = n − 1). `t` is the textbook paired t;
// it overstates the evidence because the folds of a repeated CV share training
// rows, so `t_corrected` applies Nadeau and Bengio's corrected resampled t,
// whose variance term is (1/n + n_test/n_train)·sd². The sign counts give a
// distribution-free view (a sign test) beside them.
struct PairedDifference {
    std::vector<double> per_fold;  // a − b, fold by fold in the same order as the folds
    double mean = 0.0, sd = 0.0;
    double t = 0.0, t_corrected = 0.0;  // 0 when every difference is 0; ±inf when all are equal and non-zero
    std::size_t a_better = 0, b_better = 0, ties = 0;
    std::size_t n() const { return per_fold.size(); }
};
// `test_train_ratio` is n_test / n_train of one fold (1 / (k − 1) for k-fold).
// a and b must have the same length.
PairedDifference paired_difference(std::span<const double> a, std::span<const double> b, double test_train_ratio);

// "k of n (p %)" for reports.
struct Count {
    std::size_t k = 0;
    std::size_t n = 0;
    double fraction() const;
};

}  // namespace rollsense::learn
