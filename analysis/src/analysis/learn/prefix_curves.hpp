// Identification before the roll ends: accuracy against the share of the roll
// seen (docs/identification.md, "Before the roll ends"). Plain data, held by
// an Evaluation and written to evaluation.json; prefix_evaluation.hpp makes it.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rollsense::learn {

// What a roll at one speed lasts after the clock's zero (series/contact_clock.hpp),
// for reading the curves in samples and seconds (medians over the dataset's
// trials of that speed with a clock). Prefixes are cut in clock units.
struct NominalLength {
    std::string speed;
    double samples = 0.0;    // median samples from the clock's zero to the end of the recording
    double seconds = 0.0;    // median seconds from the clock's zero to the last timestamp
    std::size_t trials = 0;  // the speed's trials with a clock (the medians' population)
};

// One point of a curve: the out-of-fold predictions at one fraction.
struct PrefixPoint {
    double fraction = 0.0;
    double seconds = 0.0;          // per-speed curves: fraction × the speed's nominal seconds after the clock's zero; 0 overall
    std::size_t total = 0;         // test predictions asked for (trials × repetitions)
    std::size_t correct = 0;
    std::size_t no_decision = 0;   // the prefix gave the classifier no input (counted wrong)
    double accuracy() const { return total ? static_cast<double>(correct) / static_cast<double>(total) : 0.0; }
};

struct PrefixSpeedCurve {
    std::string speed;
    std::vector<PrefixPoint> points;  // one per fraction
};

struct PrefixCurve {
    std::string classifier;           // as the evaluation names it
    std::string input;                // features | series
    std::vector<PrefixPoint> points;  // all speeds, one per fraction
    std::vector<PrefixSpeedCurve> by_speed;
    // The smallest fraction whose accuracy is at least 95 % of the accuracy at
    // the largest fraction (the full roll when 1.0 is among the fractions).
    std::optional<double> fraction_95;
};

struct PrefixCurves {
    std::vector<double> fractions;
    int folds = 0, repeats = 0;  // the evaluation's first `repeats` partitions
    double units = 0.0;          // the nominal roll in clock units: what the fractions are fractions of
    std::vector<NominalLength> nominal;
    std::vector<PrefixCurve> classifiers;
};

// The statement every presentation of the curves carries.
inline constexpr const char* kPrefixTimingNote =
    "Prefixes are cut on the contact's own clock (from the half-way rise of the first touched sensor's bump, in "
    "units of its full width at half maximum), so timing is relative to the contact and a faster crossing shows "
    "about the same part of it; how well that bump's width stands for the whole contact's length varies with the "
    "object and with which sensor it is, so some crossing-speed information can remain.";

// What to compute: the fractions, and how many of the evaluation's partitions
// (the default: one k-fold per fraction).
struct PrefixOptions {
    std::vector<double> fractions = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    int repeats = 1;
    unsigned threads = 0;
    std::function<void(const std::string&)> progress;
};

// Text block for evaluation.txt.
std::string format_prefix_curves(const PrefixCurves& curves);

}  // namespace rollsense::learn
