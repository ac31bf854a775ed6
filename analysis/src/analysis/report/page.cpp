// Assembles the report page from the figures and tables, and writes it.
#include <algorithm>
#include <cstdio>
#include <map>

#include "rollsense/atomic_file.hpp"
#include "analysis/learn/inputs.hpp"
#include "analysis/report/breakdown.hpp"
#include "analysis/report/comparison.hpp"
#include "analysis/report/confusion_figure.hpp"
#include "analysis/report/feature_figure.hpp"
#include "analysis/report/page_style.hpp"
#include "analysis/report/peak_grid.hpp"
#include "analysis/report/provenance.hpp"
#include "analysis/report/prefix_figure.hpp"
#include "analysis/report/report.hpp"
#include "analysis/report/svg.hpp"
#include "analysis/report/tables.hpp"

#ifndef ROLLSENSE_VERSION  // the report names the software that wrote it (review: it said "unknown")
#error "ROLLSENSE_VERSION is set by analysis/CMakeLists.txt"
#endif

namespace rollsense::report {

namespace {

std::string section(const std::string& id, const std::string& title, const std::string& body) {
    return "<section id=\"" + escape_xml(id) + "\">\n<h2>" + escape_xml(title) + "</h2>\n" + body + "</section>\n";
}

std::string figure(const std::string& svg, const std::string& caption) {
    return "<figure>\n" + svg + "<figcaption>" + caption + "</figcaption>\n</figure>\n";
}

// The paper's "time per identification": how long a roll at the fastest speed
// records for. The fastest speed is the one with the shortest mean recording.
ExtraRow identification_time(const DatasetReader& dataset) {
    ExtraRow row{"time per identification (longest recording at the fastest speed)", "\u2013", "under 3.4 s"};
    const double rate = dataset.info().sample_rate_hz;
    std::map<std::string, std::pair<double, double>> by_speed;  // sum of samples, count
    for (const auto& t : dataset.trials()) {
        auto& s = by_speed[t.info.speed];
        s.first += static_cast<double>(t.samples);
        s.second += 1.0;
    }
    if (by_speed.empty() || !(rate > 0.0)) return row;
    const auto fastest = std::min_element(by_speed.begin(), by_speed.end(), [](const auto& a, const auto& b) {
        return a.second.first / a.second.second < b.second.first / b.second.second;
    });
    std::size_t longest = 0;
    for (const auto& t : dataset.trials())
        if (t.info.speed == fastest->first) longest = std::max(longest, t.samples);
    row.label = "time per identification (longest recording at the fastest speed, " + fastest->first + ")";
    row.ours = fixed(static_cast<double>(longest) / rate, 2) + " s";
    return row;
}

// Trials whose file could not be read were skipped by the feature extraction:
// each is named with the reason, so the file can be fixed.
std::string unreadable_trials(const std::vector<features::FeatureRow>& rows) {
    std::string items;
    for (const auto& r : rows)
        if (!r.clean && r.reason.rfind("unreadable", 0) == 0)
            items += "<li><code>" + escape_xml(r.trial_id) + "</code>: " + escape_xml(r.reason) + "</li>\n";
    if (items.empty()) return {};
    return "<p class=\"note\" id=\"unreadable-trials\">Skipped: trials whose file could not be read (fix the file and "
           "run the analysis again):</p>\n<ul>\n" + items + "</ul>\n";
}

}  // namespace

std::filesystem::path report_path(const ReportInputs& in) {
    return in.output.empty() ? in.dataset_dir / "report.html" : in.output;
}

learn::EvaluationFiles evaluation_files_of(const std::filesystem::path& page) {
    const std::string stem = page.stem().string();
    const std::string name = stem == "report"             ? std::string("evaluation")
                             : stem.rfind("report-", 0) == 0 ? "evaluation" + stem.substr(6)
                                                             : stem + "-evaluation";
    return {page.parent_path() / (name + ".txt"), page.parent_path() / (name + ".json")};
}

Result<std::string> render_report(const ReportInputs& in) {
    auto dataset = DatasetReader::open(in.dataset_dir);
    if (!dataset) return dataset.error();
    // Provenance only: an unreadable run-info.csv is said on the page, not a reason to lose an evaluation that may
    // have taken hours (review: the report failed after the cross-validation).
    auto run_info = read_run_info(in.dataset_dir);
    const std::string run_info_problem = run_info ? "" : run_info.error().message;
    if (!run_info) run_info = csv::KeyValues{};
    // The first classifier's figures fill the paper's sections; a comparison
    // of several gets its own section.
    const learn::EvaluationReport& ev = in.evaluation.primary();
    const auto& b = ev.baseline;
    const bool several = in.evaluation.classifiers.size() > 1;

    std::string body;
    const std::string name = in.dataset_dir.filename().empty() ? in.dataset_dir.parent_path().filename().string()
                                                               : in.dataset_dir.filename().string();
    body += "<header>\n<h1>Object identification report: " + escape_xml(name) + "</h1>\n";
    body += "<p class=\"lead\">Dataset <code>" + escape_xml(in.dataset_dir.string()) + "</code>, " +
            std::to_string(ev.trials) + " trials, " + std::to_string(ev.clean) + " " + learn::used_trials_word(in.evaluation) +
            ". Figures and analyses of " +
            "the E-TRoll paper computed for this data.</p>\n";
    body += "<p class=\"headline\" id=\"headline\">Accuracy " + mean_sd(b.mean, b.sd) + " (" + escape_xml(ev.name) + ", " + std::to_string(b.repeats) +
            " \u00d7 " + std::to_string(b.folds) + "-fold CV), 95\u00a0% interval " + fixed(100.0 * b.wilson.low, 1) +
            "\u2013" + fixed(100.0 * b.wilson.high, 1) + "\u00a0%; the paper: 90.5\u00a0%.</p>\n";
    // Method caveat: a series time axis outside the paper's timing rule taints every figure below.
    if (const auto caveat = learn::time_axis_caveat(in.evaluation); !caveat.empty())
        body += "<p class=\"headline\" id=\"time-axis-caveat\">Method: " + escape_xml(caveat) + ".</p>\n";
    body += "</header>\n";
    body += "<nav><ol><li><a href=\"#sec-accuracy\">Accuracy</a></li>" +
            std::string(several ? "<li><a href=\"#sec-compare\">Classifiers compared</a></li>" : "") + std::string(in.evaluation.prefixes ? "<li><a href=\"#sec-prefixes\">Before the roll ends</a></li>" : "") + "<li><a href=\"#sec-confusion\">Confusion "
            "matrix</a></li><li><a href=\"#sec-breakdown\">By speed and object</a></li><li><a "
            "href=\"#sec-paper\">The paper's analyses</a></li><li><a href=\"#sec-peaks\">Peak plots</a></li><li><a "
            "href=\"#sec-features\">Features</a></li><li><a href=\"#sec-tuning\">Tuning</a></li><li><a "
            "href=\"#sec-provenance\">Provenance</a></li></ol></nav>\n";

    // Review: with --trials all, the page never said that the series rule chose the trials.
    const std::string selection = learn::selection_line(in.evaluation);
    body += section("sec-accuracy", "Accuracy", accuracy_table(ev, ev.name, learn::used_trials_word(in.evaluation)) +
                                                    "<p class=\"note\">" + escape_xml(learn::summarize_rejections(in.rows)) +
                                                    "</p>\n" +
                                                    (selection.empty() ? "" : "<p class=\"note\" id=\"trial-selection\">" + escape_xml(selection) + "</p>\n") +
                                                    unreadable_trials(in.rows));
    if (several)
        body += section("sec-compare", "Classifiers compared on the same folds",
                        comparison_section(in.evaluation, in.catalogue) +
                            "<p class=\"note\">The sections below show the first classifier, " +
                            escape_xml(ev.name) + ".</p>\n");

    body += section("sec-confusion", "Confusion matrix (cf. the paper's Fig. 9)",
                    figure(confusion_figure(b.confusion, in.catalogue, "fig-confusion", "Confusion matrix"),
                           "Out-of-fold predictions pooled over all " + std::to_string(b.repeats) +
                               " repetitions of the " + std::to_string(b.folds) +
                               "-fold CV (each clean trial counted once per repetition). Rows: true object; "
                               "columns: predicted; shading: share of the row. TPR: true-positive rate per object. "
                               "Thick lines separate cylinders, large and small polygonal prisms."));

    const Breakdown split = breakdown(in.rows, ev, in.catalogue, in.evaluation.trial_ids);
    body += section("sec-breakdown", "Clean rate and accuracy by speed and by object",
                    breakdown_table(split.by_speed, "speed", nullptr) +
                        breakdown_table(split.by_object, "object", &b.confusion) +
                        "<p class=\"note\">\u201cfirst CV\u201d: the out-of-fold predictions of the first "
                        "repetition (one k-fold CV, as the paper ran). TPR: pooled over all repetitions, as in the "
                        "confusion matrix." +
                        std::string(in.evaluation.selection == "series_accepted"
                                        ? " Clean: the paper's peak rule; the first CV took every trial the series "
                                          "rule accepts, so a row may have more trials evaluated than clean."
                                        : "") +
                        "</p>\n");

    body += section("sec-paper", "The paper's analyses, side by side", paper_comparison_table(ev.analysis, {identification_time(*dataset)}) +
                        "<p class=\"note\">This data: the first repetition's out-of-fold predictions. Paper: Table "
                        "and text of the E-TRoll paper (method.md \u00a76); a bare number is one the paper gives "
                        "without its denominator.</p>\n");

    const TrialSelection sel = select_trials(*dataset, in.rows, in.catalogue);
    auto grid = peak_grid_figure(*dataset, sel, in.settings, "fig-peaks");
    if (!grid) return grid.error();
    body += section("sec-peaks", "Peak plots (cf. the paper's Fig. 7)",
                    figure(*grid, "Smoothed readings of ch1\u2013ch3 for one trial per object and speed: the clean "
                                  "trial with the lowest repetition, or a rejected one (red dashed frame) when none "
                                  "is clean."));

    std::string features_body;
    if (auto pick = pick_feature_trial(*dataset, in.rows, in.catalogue)) {
        auto t = load_plotted_trial(*dataset, dataset->trials()[*pick], in.settings);
        if (!t) return t.error();
        features_body = figure(feature_figure(*t, "fig-features"),
                               "The features of trial " + escape_xml(t->info.id) +
                                   " on its smoothed peaks: amplitude at the maximum, peak width between the 5\u00a0% "
                                   "crossings (tick: its mid-point, which the skewness compares with the maximum), "
                                   "half-width at 50\u00a0%, and the time between maxima.") +
                        feature_values_table(*t);
    } else {
        features_body = "<p class=\"note\">No clean trial to draw the features on.</p>\n";
    }
    body += section("sec-features", "Features on one trial (cf. the paper's Fig. 8)", features_body);

    if (in.evaluation.prefixes)
        body += section("sec-prefixes", "Identification before the roll ends", prefix_section(*in.evaluation.prefixes));

    std::string tuning = protocol_table(ev) + hyperparameter_table(ev);
    if (ev.tuned)
        tuning += "<p class=\"note\">The optimiser evaluated " + std::to_string(ev.tuned->search.history.size()) +
                  " points; the paper's 90.5\u00a0% was obtained this optimistic way.</p>\n";
    body += section("sec-tuning", "Hyperparameters and tuning", tuning);

    KeyValues made = {{"report generated (UTC)", utc_timestamp()},
                      {"report software version", ROLLSENSE_VERSION},
                      {"report command line", in.command_line.empty() ? std::string("(not given)") : in.command_line},
                      {"evaluation seconds", fixed(in.evaluation.seconds, 1)}};
    const DatasetInfo& di = dataset->info();
    KeyValues recorded = {{"profile", di.profile},
                          {"seed", std::to_string(di.seed)},
                          {"recording software version", di.software_version},
                          {"sample rate (Hz)", fixed(di.sample_rate_hz, 2)}};
    // Inside a run, that run is the recording: a run-info.csv on disk is then
    // an earlier, interrupted run's (this one resumed it) and is replaced at the end.
    std::string prov;
    if (!in.recording_run.empty())
        prov = "<h3>Recording (this run, still in progress: its run-info.csv is written when it ends)</h3>\n" +
               key_value_table(in.recording_run);
    else if (!run_info->empty())
        prov = "<h3>Recording (run-info.csv)</h3>\n" + key_value_table(*run_info);
    else if (!run_info_problem.empty())
        prov = "<h3>Recording (run-info.csv)</h3>\n<p class=\"note\">run-info.csv could not be read: " +
               escape_xml(run_info_problem) + "</p>\n";
    else
        prov = "<h3>Recording (run-info.csv)</h3>\n<p class=\"note\">No run-info.csv: the dataset was not recorded "
               "by rollsense run.</p>\n";
    prov += "<h3>Dataset (dataset-info.csv)</h3>\n" + key_value_table(recorded);
    prov += "<h3>This report</h3>\n" + key_value_table(made);
    body += section("sec-provenance", "Provenance", prov);

    return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" "
           "content=\"width=device-width, initial-scale=1\">\n<meta name=\"generator\" content=\"rollsense " ROLLSENSE_VERSION
           "\">\n<title>rollsense report: " +
           escape_xml(name) + "</title>\n<style>" + kPageStyle + "</style>\n</head>\n<body>\n" + body +
           "</body>\n</html>\n";
}

Result<std::filesystem::path> write_report(const ReportInputs& in) {
    auto html = render_report(in);
    if (!html) return html.error();
    const auto path = report_path(in);
    if (auto st = write_file_atomic(path, *html); !st)
        return Error{st.code(), "cannot write the report '" + path.string() + "': " + st.message()};
    return path;
}

}  // namespace rollsense::report
