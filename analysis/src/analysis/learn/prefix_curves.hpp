// Identification before the roll ends: accuracy against the share of the roll
// seen (docs/identification.md, "Before the roll ends"). Plain data, held by
// an Evaluation and written to evaluation.json; prefix_evaluation.hpp makes it.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rollsense::learn {

// A speed's nominal roll after the contact's onset: how long a recording at
// that speed goes on once the object first presses the array, known before
// the roll (here the median over the dataset's trials of that speed), so a
// live run that reads the contact's clock can cut its prefixes the same way.
// Prefixes are cut in `units` (the contact's own time); samples and seconds
// are for reading the curves.
struct NominalLength {
    std::string speed;
    double samples = 0.0;    // median samples from the onset to the end of the recording
    double seconds = 0.0;    // median seconds from the onset to the last timestamp
    double units = 0.0;      // median of those samples ÷ the trial's unit (series::ContactClock)
    std::size_t trials = 0;  // the speed's trials with a unit (the medians' population)
};

// One point of a curve: the out-of-fold predictions at one fraction.
struct PrefixPoint {
    double fraction = 0.0;
    double seconds = 0.0;          // per-speed curves: fraction × the speed's nominal seconds (after the onset); 0 overall
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
    std::vector<NominalLength> nominal;
    std::vector<PrefixCurve> classifiers;
};

// The statement every presentation of the curves carries.
inline constexpr const char* kPrefixTimingNote =
    "Prefixes are cut on the contact's own clock: from the onset, in units of the time the first sensor takes to be "
    "passed, so timing is relative to the contact and a faster crossing does not show more of it; the earliest cut "
    "is where that unit is known.";

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
