// The plain-text summary printed on the terminal at the end of a run.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/learn/inputs.hpp"
#include "analysis/report/breakdown.hpp"
#include "analysis/report/report.hpp"
#include "analysis/report/svg.hpp"

namespace rollsense::report {

namespace {

// Plain ASCII-friendly percent for terminals ("91.2 %").
std::string pct(double fraction) {
    if (!std::isfinite(fraction)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * fraction);
    return buf;
}

// " +- 0.9" after a percentage, or " (one repetition: no spread)".
std::string pm(double sd) {
    if (!learn::has_spread(sd)) return std::string(" (") + learn::no_spread_text + ")";
    char buf[32];
    std::snprintf(buf, sizeof buf, " +- %.1f", 100.0 * sd);
    return buf;
}

}  // namespace

std::string text_summary(const ReportInputs& in) {
    const auto& ev = in.evaluation.primary();
    const auto& b = ev.baseline;
    std::string out;
    char buf[512];
    std::snprintf(buf, sizeof buf, "Identification of %s\n", in.dataset_dir.string().c_str());
    out += buf;
    out += "  " + learn::summarize_rejections(in.rows) + "\n";
    // A series classifier's trials need not be the clean ones: which were used, and how it did on the refused ones.
    const std::string selection = learn::selection_line(in.evaluation);
    for (std::size_t at = 0; at < selection.size();) {
        const auto end = std::min(selection.find('\n', at), selection.size() - 1);
        out += "  " + selection.substr(at, end - at + 1);
        at = end + 1;
    }
    if (const auto caveat = learn::time_axis_caveat(in.evaluation); !caveat.empty()) out += "  NOTE: " + caveat + "\n";
    std::snprintf(buf, sizeof buf,
                  "  accuracy %s%s (%s, %d x %d-fold CV), 95 %% interval %.1f-%.1f %%; paper 90.5 %%\n",
                  pct(b.mean).c_str(), pm(b.sd).c_str(), ev.name.c_str(), b.repeats, b.folds, 100.0 * b.wilson.low,
                  100.0 * b.wilson.high);
    out += buf;
    for (const auto& s : ev.scheme_cv) {
        std::snprintf(buf, sizeof buf, "  %s: %s%s (%d x %d-fold, groups held out whole)\n",
                      s.scheme.describe().c_str(), pct(s.cv.mean).c_str(), pm(s.cv.sd).c_str(), s.cv.repeats, s.cv.folds);
        out += buf;
        if (s.nested) {
            std::snprintf(buf, sizeof buf, "    tuned on folds of the same scheme, nested CV (honest): %s%s\n",
                          pct(s.nested->mean).c_str(), pm(s.nested->sd).c_str());
            out += buf;
        }
    }
    if (ev.tuned) {
        std::snprintf(buf, sizeof buf, "  tuned, scored on the same folds (optimistic, the paper's protocol): %s\n",
                      pct(ev.tuned->same_folds_accuracy).c_str());
        out += buf;
    }
    if (ev.nested) {
        std::snprintf(buf, sizeof buf, "  tuned, nested CV (honest): %s%s\n", pct(ev.nested->mean).c_str(),
                      pm(ev.nested->sd).c_str());
        out += buf;
    }
    // Further classifiers of a comparison: their figure and the paired difference to the first.
    for (std::size_t i = 1; i < in.evaluation.classifiers.size(); ++i) {
        const auto& c = in.evaluation.classifiers[i];
        std::snprintf(buf, sizeof buf, "  compared: %s %s%s", c.name.c_str(), pct(c.baseline.mean).c_str(),
                      pm(c.baseline.sd).c_str());
        out += buf;
        for (const auto& p : in.evaluation.paired)
            if (p.a == 0 && p.b == i) {
                std::snprintf(buf, sizeof buf, "; first minus it %+.1f points per fold (corrected t %.2f)",
                              100.0 * p.difference.mean, p.difference.t_corrected);
                out += buf;
            }
        out += "\n";
    }
    // The objects most often confused: the ones a reader looks for first.
    const Breakdown split = breakdown(in.rows, ev, in.catalogue, in.evaluation.trial_ids);
    const std::vector<double> tpr = b.confusion.true_positive_rates();
    std::vector<std::size_t> idx(tpr.size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    std::stable_sort(idx.begin(), idx.end(), [&](std::size_t x, std::size_t y) {
        const double a = std::isfinite(tpr[x]) ? tpr[x] : 2.0, c = std::isfinite(tpr[y]) ? tpr[y] : 2.0;
        return a < c;
    });
    if (!idx.empty()) {
        out += "  weakest objects (TPR):";
        for (std::size_t k = 0; k < std::min<std::size_t>(3, idx.size()); ++k)
            out += " " + b.confusion.classes[idx[k]] + " " + pct(tpr[idx[k]]) + (k + 1 < std::min<std::size_t>(3, idx.size()) ? "," : "");
        out += "\n";
    }
    if (!split.by_speed.empty()) {
        out += "  by speed (clean rate, accuracy):";
        for (std::size_t k = 0; k < split.by_speed.size(); ++k) {
            const auto& s = split.by_speed[k];
            out += " " + s.label + ": " + pct(s.clean_rate()) + ", " + pct(s.accuracy()) +
                   (k + 1 < split.by_speed.size() ? ";" : "");
        }
        out += "\n";
    }
    out += "  report: " + report_path(in).string() + "\n";
    return out;
}

}  // namespace rollsense::report
