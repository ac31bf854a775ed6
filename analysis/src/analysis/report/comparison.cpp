#include "analysis/report/comparison.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/learn/bayes_opt.hpp"
#include "analysis/report/confusion_figure.hpp"
#include "analysis/report/object_order.hpp"
#include "analysis/report/svg.hpp"
#include "analysis/report/tables.hpp"

namespace rollsense::report {
namespace {

std::string td(const std::string& text, bool number = false) {
    return std::string(number ? "<td class=\"num\">" : "<td>") + escape_xml(text) + "</td>";
}

std::string th(const std::string& text) { return "<th>" + escape_xml(text) + "</th>"; }

std::string params_text(const ParamSet& p) {
    std::string s;
    for (const auto& [k, v] : p.values()) s += (s.empty() ? "" : ", ") + k + "=" + format_param(v);
    return s.empty() ? "(defaults)" : s;
}

std::string accuracy_rows(const learn::Evaluation& ev) {
    std::string h = "<table class=\"numbers\" id=\"compare-accuracy\"><thead><tr>" + th("classifier") +
                    th("parameters") + th("accuracy, mean \u00b1 sd over repetitions") +
                    th("pooled out-of-fold correct") + th("95 % Wilson interval (pooled)") + "</tr></thead><tbody>\n";
    for (const auto& c : ev.classifiers) {
        const auto& b = c.baseline;
        h += "<tr>" + td(c.name) + td(params_text(c.params)) +
             td(mean_sd(b.mean, b.sd), true) +
             td(std::to_string(b.correct) + " of " + std::to_string(b.total), true) +
             td("[" + fixed(100.0 * b.wilson.low, 1) + ", " + fixed(100.0 * b.wilson.high, 1) + "]\u00a0%", true) +
             "</tr>\n";
    }
    return h + "</tbody></table>\n";
}

std::string per_class_rows(const learn::Evaluation& ev, const std::vector<learn::ObjectShape>& catalogue) {
    std::string h = "<table class=\"numbers\" id=\"compare-per-class\"><thead><tr>" + th("object");
    for (const auto& c : ev.classifiers) h += th(c.name);
    h += "</tr></thead><tbody>\n";
    std::vector<std::vector<double>> tpr;
    for (const auto& c : ev.classifiers) tpr.push_back(c.baseline.confusion.true_positive_rates());
    for (std::size_t i : order_objects(ev.classes, catalogue).order) {
        h += "<tr>" + td(ev.classes[i]);
        for (const auto& t : tpr) h += td(i < t.size() ? percent(t[i]) : "\u2013", true);
        h += "</tr>\n";
    }
    return h + "</tbody></table>\n";
}

std::string paired_rows(const learn::Evaluation& ev) {
    std::string h = "<table class=\"numbers\" id=\"compare-paired\"><thead><tr>" + th("a \u2212 b") +
                    th("mean (points)") + th("sd (points)") + th("folds n") + th("paired t (df n\u22121)") +
                    th("corrected t (Nadeau\u2013Bengio)") + th("folds a better / b better / tied") +
                    "</tr></thead><tbody>\n";
    for (const auto& p : ev.paired) {
        const auto& d = p.difference;
        h += "<tr>" + td(ev.classifiers[p.a].name + " \u2212 " + ev.classifiers[p.b].name) +
             td(fixed(100.0 * d.mean, 2), true) + td(fixed(100.0 * d.sd, 2), true) + td(std::to_string(d.n()), true) +
             td(fixed(d.t, 2), true) + td(fixed(d.t_corrected, 2), true) +
             td(std::to_string(d.a_better) + " / " + std::to_string(d.b_better) + " / " + std::to_string(d.ties),
                true) +
             "</tr>\n";
    }
    return h + "</tbody></table>\n";
}

}  // namespace

std::string paired_difference_figure(const learn::Evaluation& ev, const std::string& id) {
    // Names go above their row (they can be long: plugin and parameters), the axis spans the width.
    const double left = 40.0, right = 40.0, top = 30.0, row_h = 60.0, plot_w = 640.0;
    const double height = top + row_h * static_cast<double>(std::max<std::size_t>(1, ev.paired.size())) + 50.0;
    Svg svg(left + plot_w + right, height, id, "Paired per-fold accuracy differences");
    // A symmetric axis around zero, wide enough for every fold's difference.
    double reach = 0.01;
    for (const auto& p : ev.paired)
        for (double d : p.difference.per_fold)
            if (std::isfinite(d)) reach = std::max(reach, std::abs(d));
    reach = std::ceil(reach * 100.0 / 2.0) * 2.0 / 100.0;
    const LinearScale x{-reach, reach, left, left + plot_w};
    const double bottom = height - 50.0;
    const Stroke axis{"#444", 1.0, ""}, zero{"#888", 1.0, "4 3"}, bar{"#c0392b", 2.5, ""};
    svg.line(left, bottom, left + plot_w, bottom, axis);
    for (int k = -2; k <= 2; ++k) {
        const double v = reach * k / 2.0;
        svg.line(x(v), bottom, x(v), bottom + 5.0, axis);
        svg.text(x(v), bottom + 18.0, fixed(100.0 * v, 1), {11.0, Anchor::middle});
    }
    svg.line(x(0.0), top - 10.0, x(0.0), bottom, zero);
    svg.text(left + plot_w / 2.0, bottom + 38.0, "a \u2212 b, accuracy points per fold", {12.0, Anchor::middle});
    for (std::size_t r = 0; r < ev.paired.size(); ++r) {
        const auto& p = ev.paired[r];
        const double cy = top + row_h * (static_cast<double>(r) + 0.5);
        svg.text(left, cy - 14.0, ev.classifiers[p.a].name + " \u2212 " + ev.classifiers[p.b].name,
                 {12.0, Anchor::start});
        const auto& d = p.difference;
        // Folds spread a little vertically so equal differences stay countable.
        for (std::size_t i = 0; i < d.per_fold.size(); ++i) {
            const double jitter = (static_cast<double>(i % 5) - 2.0) * 3.0;
            svg.circle(x(d.per_fold[i]), cy + jitter, 2.5, "#2e6fb7", {"#1d4f86", 0.5, ""});
        }
        svg.line(x(d.mean - d.sd), cy + 14.0, x(d.mean + d.sd), cy + 14.0, bar);
        svg.line(x(d.mean), cy + 8.0, x(d.mean), cy + 20.0, bar);
    }
    return svg.str();
}

std::string comparison_section(const learn::Evaluation& ev, const std::vector<learn::ObjectShape>& catalogue) {
    std::string body = "<p>" + std::to_string(ev.classifiers.size()) + " classifiers, each scored on the same " +
                       std::to_string(ev.plan.repeats()) + " \u00d7 " + std::to_string(ev.plan.folds) +
                       "-fold partitions (" + (ev.plan.grouped ? "grouped" : "stratified") + ", seeds " +
                       std::to_string(ev.plan.seeds.front()) + "\u2013" + std::to_string(ev.plan.seeds.back()) +
                       "), so their per-fold accuracies pair up.</p>\n";
    body += accuracy_rows(ev);
    body += "<h3>Per-class accuracy (TPR, pooled over repetitions)</h3>\n" + per_class_rows(ev, catalogue);
    body += "<h3>Paired differences</h3>\n" + paired_rows(ev);
    body += "<figure>\n" + paired_difference_figure(ev, "fig-paired") +
            "<figcaption>Every fold of every repetition: accuracy of a minus accuracy of b on the same test trials "
            "(dots); the red bar is the mean \u00b1 1 sd. The paired t treats the folds as independent, which "
            "overstates the evidence because folds share training trials; the corrected t (Nadeau and Bengio) "
            "allows for that and is the one to read.</figcaption>\n</figure>\n";
    for (std::size_t i = 0; i < ev.classifiers.size(); ++i) {
        const auto& c = ev.classifiers[i];
        body += "<figure>\n" +
                confusion_figure(c.baseline.confusion, catalogue, "fig-confusion-" + std::to_string(i + 1),
                                 "Confusion matrix of " + c.name) +
                "<figcaption>" + escape_xml(c.name) +
                ": out-of-fold predictions pooled over all repetitions.</figcaption>\n</figure>\n";
    }
    return body;
}

}  // namespace rollsense::report
