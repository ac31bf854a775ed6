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
                    const std::vector<learn::ObjectShape>& catalogue, const std::vector<std::string>& trial_ids) {
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
    // The evaluation's rows are its trials (Evaluation::trial_ids), not
    // necessarily every clean row: beside a series classifier the trials the
    // series rule refuses are left out too.
    std::map<std::string, std::size_t> row_of_trial;
    for (std::size_t i = 0; i < rows.size(); ++i) row_of_trial.emplace(rows[i].trial_id, i);
    const auto& predicted = report.baseline.first_predicted;
    for (std::size_t i = 0; i < trial_ids.size() && i < predicted.size(); ++i) {
        const auto it = row_of_trial.find(trial_ids[i]);
        if (it == row_of_trial.end()) continue;
        const auto& r = rows[it->second];
        const int p = predicted[i];
        const bool right = p >= 0 && static_cast<std::size_t>(p) < report.classes.size() &&
                           report.classes[static_cast<std::size_t>(p)] == r.object;
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
