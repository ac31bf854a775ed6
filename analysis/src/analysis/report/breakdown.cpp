#include "analysis/report/breakdown.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/report/object_order.hpp"
#include "analysis/report/peak_grid.hpp"

namespace rollsense::report {

double BreakdownRow::clean_rate() const {
    return trials == 0 ? std::numeric_limits<double>::quiet_NaN()
                       : static_cast<double>(clean) / static_cast<double>(trials);
}

double BreakdownRow::accuracy() const {
    return evaluated == 0 ? std::numeric_limits<double>::quiet_NaN()
                          : static_cast<double>(correct) / static_cast<double>(evaluated);
}

Breakdown breakdown(const std::vector<features::FeatureRow>& rows, const learn::EvaluationReport& report,
                    const std::vector<learn::ObjectShape>& catalogue) {
    std::map<std::string, BreakdownRow> speeds, objects;
    std::vector<std::string> speed_labels, object_labels;
    for (const auto& r : rows) {
        for (auto* m : {&speeds, &objects}) {
            const std::string& key = m == &speeds ? r.speed : r.object;
            auto [it, fresh] = m->try_emplace(key);
            if (fresh) {
                it->second.label = key;
                (m == &speeds ? speed_labels : object_labels).push_back(key);
            }
            ++it->second.trials;
            it->second.clean += r.clean;
        }
    }
    // Table row i of the evaluation is the i-th clean row, classes by name:
    // the same mapping learn::evaluate() used.
    std::vector<std::size_t> row_of;
    const FeatureTable table = features::to_feature_table(rows, &row_of);
    const auto& predicted = report.baseline.first_predicted;
    for (std::size_t i = 0; i < row_of.size() && i < predicted.size(); ++i) {
        const auto& r = rows[row_of[i]];
        const bool right = predicted[i] == table.y[i];
        for (auto* b : {&speeds.at(r.speed), &objects.at(r.object)}) {
            ++b->evaluated;
            b->correct += right;
        }
    }
    Breakdown out;
    for (const auto& s : sorted_speeds(speed_labels)) out.by_speed.push_back(speeds.at(s));
    std::sort(object_labels.begin(), object_labels.end());
    for (std::size_t i : order_objects(object_labels, catalogue).order) out.by_object.push_back(objects.at(object_labels[i]));
    return out;
}

}  // namespace rollsense::report
