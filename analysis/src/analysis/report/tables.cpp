#include "analysis/report/tables.hpp"

#include <cstdio>
#include <type_traits>

#include "analysis/report/svg.hpp"

namespace rollsense::report {

namespace {

std::string td(const std::string& text, bool number = false) {
    return std::string(number ? "<td class=\"num\">" : "<td>") + escape_xml(text) + "</td>";
}

std::string th(const std::string& text) {
    return "<th>" + escape_xml(text) + "</th>";
}

std::string count(const learn::Count& c) {
    if (c.n == 0 && c.k == 0) return "n/a";  // nothing to count: no such trials (or no figure in the paper)
    if (c.n == 0) return std::to_string(c.k);
    return std::to_string(c.k) + " / " + std::to_string(c.n) + " (" + percent(c.fraction()) + ")";
}

std::string interval(const learn::Interval& i) {
    return "[" + fixed(100.0 * i.low, 1) + ", " + fixed(100.0 * i.high, 1) + "]\u00a0%";
}

}  // namespace

std::string mean_sd(double mean, double sd) {
    if (!learn::has_spread(sd)) return fixed(100.0 * mean, 1) + "\u00a0% (" + learn::no_spread_text + ")";
    return fixed(100.0 * mean, 1) + " \u00b1 " + fixed(100.0 * sd, 1) + "\u00a0%";
}

std::string format_param(const ParamValue& value) {
    return std::visit(
        [](const auto& v) -> std::string {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
            else if constexpr (std::is_same_v<T, std::int64_t>) return std::to_string(v);
            else if constexpr (std::is_same_v<T, double>) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "%g", v);
                return buf;
            } else if constexpr (std::is_same_v<T, std::string>) return v;
            else {
                std::string s = "[";
                for (std::size_t i = 0; i < v.size(); ++i) {
                    if (i) s += ", ";
                    if constexpr (std::is_same_v<T, std::vector<std::string>>) s += v[i];
                    else {
                        char buf[32];
                        std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v[i]));
                        s += buf;
                    }
                }
                return s + "]";
            }
        },
        value);
}

std::string accuracy_table(const learn::EvaluationReport& r, const std::string& classifier,
                           const std::string& trials_word) {
    const auto& b = r.baseline;
    std::string h = "<table class=\"numbers\" id=\"accuracy\"><tbody>\n";
    h += "<tr>" + th("classifier") + td(classifier) + "</tr>\n";
    h += "<tr>" + th("trials / " + trials_word) + td(std::to_string(r.trials) + " / " + std::to_string(r.clean), true) + "</tr>\n";
    h += "<tr>" + th("protocol") +
         td(std::to_string(b.repeats) + " \u00d7 stratified " + std::to_string(b.folds) + "-fold CV, preset parameters") +
         "</tr>\n";
    h += "<tr>" + th("accuracy, mean \u00b1 sd over repetitions") + td(mean_sd(b.mean, b.sd), true) + "</tr>\n";
    h += "<tr>" + th("pooled out-of-fold predictions") +
         td(std::to_string(b.correct) + " of " + std::to_string(b.total) + " correct", true) + "</tr>\n";
    h += "<tr>" + th("95 % Wilson interval (pooled)") + td(interval(b.wilson), true) + "</tr>\n";
    // Grouped / blocked CV beside it: what the figure owes to neighbouring rolls (rollsense evaluate --cv).
    for (const auto& s : r.scheme_cv)
        h += "<tr>" + th(s.scheme.describe() + ", " + std::to_string(s.cv.repeats) + " \u00d7 " +
                         std::to_string(s.cv.folds) + "-fold, groups held out whole") +
             td(mean_sd(s.cv.mean, s.cv.sd) + " (Wilson " + interval(s.cv.wilson) + ")", true) + "</tr>\n";
    h += "<tr>" + th("paper (5-fold CV, tuned on the same folds)") + td(percent(0.905), true) + "</tr>\n";
    return h + "</tbody></table>\n";
}

std::string breakdown_table(const std::vector<BreakdownRow>& rows, const std::string& what,
                            const learn::ConfusionMatrix* pooled) {
    std::string h = "<table class=\"numbers\" id=\"by-" + escape_xml(what) + "\"><thead><tr>" + th(what) +
                    th("trials") + th("clean") + th("clean rate") + th("correct (first CV)") + th("accuracy (first CV)");
    if (pooled) h += th("TPR (all repetitions)");
    h += "</tr></thead><tbody>\n";
    const std::vector<double> tpr = pooled ? pooled->true_positive_rates() : std::vector<double>{};
    for (const auto& r : rows) {
        h += "<tr>" + td(r.label) + td(std::to_string(r.trials), true) + td(std::to_string(r.clean), true) +
             td(percent(r.clean_rate()), true) +
             td(std::to_string(r.correct) + " / " + std::to_string(r.evaluated), true) + td(percent(r.accuracy()), true);
        if (pooled) {
            std::string cell = "\u2013";
            for (std::size_t i = 0; i < pooled->classes.size(); ++i)
                if (pooled->classes[i] == r.label) cell = percent(tpr[i]);
            h += td(cell, true);
        }
        h += "</tr>\n";
    }
    return h + "</tbody></table>\n";
}

std::string paper_comparison_table(const learn::PaperAnalysis& ours, const std::vector<ExtraRow>& extra) {
    const learn::PaperAnalysis& paper = learn::paper_figures();
    struct Line {
        const char* label;
        const learn::Count learn::PaperAnalysis::*field;
    };
    const Line lines[] = {
        {"clean trials / collected", &learn::PaperAnalysis::clean},
        {"cylinder trials clean", &learn::PaperAnalysis::cylinders_clean},
        {"polygon trials clean", &learn::PaperAnalysis::polygons_clean},
        {"accuracy, first CV repetition (correct / evaluated trials)", &learn::PaperAnalysis::accuracy},
        {"cylinder vs polygon correct", &learn::PaperAnalysis::family_correct},
        {"cylinders misclassified", &learn::PaperAnalysis::cylinders_misclassified},
        {"polygons with the correct base edge length", &learn::PaperAnalysis::polygon_edge_correct},
        {"hexagons misclassified", &learn::PaperAnalysis::hexagons_misclassified},
        {"\u2003of those called pentagons", &learn::PaperAnalysis::hexagons_called_pentagons},
        {"pentagons misclassified", &learn::PaperAnalysis::pentagons_misclassified},
        {"\u2003of those called hexagons", &learn::PaperAnalysis::pentagons_called_hexagons},
    };
    std::string h = "<table class=\"numbers\" id=\"paper-comparison\"><thead><tr>" + th("analysis (method.md \u00a76)") +
                    th("this data") + th("paper") + "</tr></thead><tbody>\n";
    for (const auto& l : lines) {
        const bool no_count = l.field == &learn::PaperAnalysis::family_correct;
        h += "<tr>" + td(l.label) + td(count(ours.*l.field), true) +
             td(no_count ? "almost perfectly separated" : count(paper.*l.field), true) + "</tr>\n";
    }
    for (const auto& e : extra) h += "<tr>" + td(e.label) + td(e.ours, true) + td(e.paper, true) + "</tr>\n";
    h += "</tbody></table>\n";
    if (!ours.unknown_objects.empty()) {
        h += "<p class=\"note\">Objects not in the catalogue, left out of the shape rows:";
        for (const auto& u : ours.unknown_objects) h += " " + escape_xml(u);
        h += "</p>\n";
    }
    return h;
}

std::string hyperparameter_table(const learn::EvaluationReport& r) {
    std::vector<std::string> names;
    for (const auto& [k, v] : r.params.values()) names.push_back(k);
    if (r.tuned)
        for (const auto& [k, v] : r.tuned->search.best_params().values())
            if (!r.params.has(k)) names.push_back(k);
    std::string h = "<table class=\"numbers\" id=\"hyperparameters\"><thead><tr>" + th("parameter") + th("preset");
    if (r.tuned) h += th("chosen by the optimiser (one fixed partition)");
    if (r.nested)
        for (std::size_t f = 0; f < r.nested->chosen.size(); ++f) h += th("nested, outer fold " + std::to_string(f + 1));
    h += "</tr></thead><tbody>\n";
    auto cell = [](const ParamSet& p, const std::string& k) {
        const auto it = p.values().find(k);
        return it == p.values().end() ? std::string("(default)") : format_param(it->second);
    };
    for (const auto& k : names) {
        h += "<tr>" + td(k) + td(cell(r.params, k), true);
        if (r.tuned) h += td(cell(r.tuned->search.best_params(), k), true);
        if (r.nested)
            for (const auto& c : r.nested->chosen) h += td(cell(c, k), true);
        h += "</tr>\n";
    }
    if (names.empty()) h += "<tr><td colspan=\"2\">the classifier's defaults (no parameter set)</td></tr>\n";
    return h + "</tbody></table>\n";
}

std::string protocol_table(const learn::EvaluationReport& r) {
    std::string h = "<table class=\"numbers\" id=\"protocols\"><thead><tr>" + th("protocol") + th("accuracy") +
                    th("95 % Wilson interval") + th("how to read it") + "</tr></thead><tbody>\n";
    const auto& b = r.baseline;
    h += "<tr>" + td("preset, repeated CV") + td(mean_sd(b.mean, b.sd), true) + td(interval(b.wilson), true) +
         td("honest: no choice was made on the test folds (sd over repetitions; interval over the trials)") + "</tr>\n";
    if (r.tuned)
        h += "<tr class=\"optimistic\">" + td("tuned and scored on the same folds (the paper's protocol)") +
             td(percent(r.tuned->same_folds_accuracy), true) + td("\u2013", true) +
             td("optimistic: the optimiser saw the folds it is scored on") + "</tr>\n";
    if (r.nested)
        h += "<tr>" + td("nested CV (tuning inside each outer training fold)") +
             td(mean_sd(r.nested->mean, r.nested->sd), true) + td(interval(r.nested->wilson), true) +
             td("honest tuned figure: compare with the row above (its sd is over the outer folds, not repetitions)") +
             "</tr>\n";
    // Tuning under grouped / blocked CV: its tuning folds hold out the same groups (learn/tuning.hpp).
    for (const auto& s : r.scheme_cv) {
        if (s.tuned)
            h += "<tr class=\"optimistic\">" +
                 td("tuned and scored on the same folds, " + s.scheme.describe() + " (tuning folds too)") +
                 td(percent(s.tuned->same_folds_accuracy), true) + td("\u2013", true) +
                 td("optimistic: the optimiser saw the folds it is scored on") + "</tr>\n";
        if (s.nested)
            h += "<tr>" + td("nested CV, " + s.scheme.describe() + " (outer and tuning folds)") +
                 td(mean_sd(s.nested->mean, s.nested->sd), true) + td(interval(s.nested->wilson), true) +
                 td("honest tuned figure with whole groups held out, in tuning as in testing") + "</tr>\n";
    }
    if (!r.tuned)
        h += "<tr>" + td("tuned figures") + td("\u2013", true) + td("\u2013", true) +
             td("not run: pass --optimize (rollsense report) or optimize=true (rs.analyse)") + "</tr>\n";
    return h + "</tbody></table>\n";
}

std::string key_value_table(const KeyValues& entries) {
    std::string h = "<table class=\"numbers provenance\"><tbody>\n";
    for (const auto& [k, v] : entries) h += "<tr>" + th(k) + "<td><code>" + escape_xml(v) + "</code></td></tr>\n";
    return h + "</tbody></table>\n";
}

}  // namespace rollsense::report
