// The experiment report: a self-contained HTML page (inline SVG figures, no
// scripts, no network) with the paper's figures and tables for one dataset,
// and a plain-text summary for the terminal. Called at the end of the stock
// experiment and by `rollsense report DATASET`.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rollsense/features.hpp"
#include "rollsense/status.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/paper_analysis.hpp"
#include "analysis/learn/pipeline.hpp"

namespace rollsense::report {

struct ReportInputs {
    std::filesystem::path dataset_dir;            // the recorded dataset (trials are re-read for the plots)
    std::filesystem::path output;                 // empty: <dataset_dir>/report.html
    std::vector<features::FeatureRow> rows;       // every trial, clean and rejected, as evaluated
    learn::Evaluation evaluation;                 // the learning pipeline's evaluation of `rows`: one
                                                  // classifier, or several compared on the same folds
    features::FeatureSettings settings;           // the settings `rows` were extracted with
    std::string command_line;                     // what made this report (shown under provenance)
    // Made by the run that recorded the dataset (rs.analyse at its end): its
    // run-info.csv is written only when the run ends, so the run's own
    // provenance so far (command line, profile, script, seed, version) is
    // given here and shown in its place. Empty: read run-info.csv.
    std::vector<std::pair<std::string, std::string>> recording_run;
    std::vector<learn::ObjectShape> catalogue = learn::paper_objects();
};

// The page as a string (reads the dataset's manifest, run-info.csv and the
// selected trial files). Errors name the file that could not be read.
Result<std::string> render_report(const ReportInputs& inputs);

// render_report() written atomically to inputs.output; returns the path.
Result<std::filesystem::path> write_report(const ReportInputs& inputs);

// A few lines for the terminal: trials, clean rate, accuracy with interval
// beside the paper's, tuned figures, weakest objects (of the first
// classifier), and one line per further classifier compared.
std::string text_summary(const ReportInputs& inputs);

std::filesystem::path report_path(const ReportInputs& inputs);

// The evaluation.txt and evaluation.json that go with a report page, beside
// it: report.html → evaluation.txt/.json, report-NAME.html → evaluation-NAME.*
// (rs.analyse's tag), any other PAGE.html → PAGE-evaluation.*. A report
// written under another name never replaces another report's evaluation.
learn::EvaluationFiles evaluation_files_of(const std::filesystem::path& page);

}  // namespace rollsense::report
