// rollsense report DATASET: evaluate a recorded dataset and write its HTML
// report (the paper's figures and tables for this data) plus a terminal summary.
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "cli/output_paths.hpp"
#include "cli/partial_dataset.hpp"
#include "cli/paths.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/shell_words.hpp"
#include "analysis/learn/defaults.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/inputs.hpp"
#include "analysis/learn/pipeline.hpp"
#include "analysis/report/report.hpp"

namespace rollsense::cli {

// Shared with evaluate and train (cmd_evaluate.cpp, cmd_features.cpp).
using LearnSetup = learn::CommandSetup;
LearnSetup learn_setup_from_args(const Args& args, const std::vector<std::string>& extra_flags,
                                 const std::vector<std::string>& not_taken);
int run_learning_pipeline(const char* command, const Args& args, const LearnSetup& s,
                          runtime::PluginRegistry& registry, learn::PipelineResult& out,
                          bool print_rejections);  // cmd_evaluate.cpp
features::FeatureSettings feature_settings_from_args(const Args& args);

namespace {

const char* kHelp = R"(usage: rollsense report DATASET [options]

Evaluate the classifier on a recorded dataset (as 'rollsense evaluate' does)
and write a self-contained HTML report: the confusion matrix with TPR column
and the cylinder / large / small polygon blocks (the paper's Fig. 9), a grid of
smoothed peak plots per object and speed (Fig. 7), one trial's features drawn
on its peaks (Fig. 8), accuracy with interval, clean rates and accuracies per
speed and object, the paper's analyses beside the paper's numbers, the
hyperparameters, and the run's provenance. Opens in any browser without a
network; prints well. A short summary is printed on the terminal.
With several classifiers (--classifier a,b) the page compares them side by
side on the same folds. evaluation.txt and evaluation.json (docs/
evaluation-json.md) are written beside the report: report.html ->
evaluation.txt/.json, report-NAME.html -> evaluation-NAME.txt/.json, any other
PAGE.html -> PAGE-evaluation.txt/.json.

A recorded run's folder already holds its own evaluation (rs.analyse wrote
report.html and evaluation.txt/.json): report refuses to replace any of these
files, before any work. Write the new report beside them under another name
(-o DATASET/report-NAME.html), or replace them with --force. The seed
defaults to the one the dataset was recorded with, as rs.analyse used it.

options:
  -o, --output FILE   report file (default: DATASET/report.html)
  --force             replace an existing report and its evaluation files
  --folds K           k of the k-fold CV (5)
  --repeats R         repetitions of the CV with different partitions (10)
  --seed S            partition and optimiser seed (default: the seed the
                      dataset was recorded with; 1 for a dataset without one
                      or recorded with --seed 0)
  --cv LIST, --group-by COLUMN, --block N
                      grouped and blocked CV beside random k-fold, shown in
                      the accuracy table (as 'rollsense evaluate --help' says;
                      with --optimize tuned on their own folds too)
  --optimize          also run the paper's Bayesian optimisation and nested CV
  --evaluations N     with --optimize: optimiser evaluations (30)
  --no-nested         with --optimize: skip the nested CV
  --classifier LIST   classifier plugin (default {default_classifier}), or
                      several, comma-separated; NAME:KEY=VALUE gives one
                      entry its own parameters
  --set KEY=VALUE     classifier parameter for every listed classifier, repeatable
  --trials SET, --series-amplitude MODE, --series-time-axis AXIS
                      which trials are evaluated and the series rule's
                      amplitude and time axis (as 'rollsense evaluate --help'
                      says; roll_relative is outside the paper's timing rule)
  --plugin-path DIR   search classifier plugins here first (repeatable)
  -v, --verbose       debug messages;   -q, --quiet   no info messages: warnings, errors
  plus the feature options of 'rollsense features'

exit codes: 0 ok, 1 the evaluation failed, 2 bad command line (or the
            report would replace existing files without --force),
            3 DATASET or a plugin is wrong, 5 the report could not be written)";

// The report's files that exist already, by name ("report.html, evaluation.txt").
std::string existing(const std::vector<std::filesystem::path>& files) {
    std::string names;
    std::error_code ec;
    for (const auto& f : files)
        if (std::filesystem::exists(f, ec)) names += (names.empty() ? "" : ", ") + f.filename().string();
    return names;
}

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    LearnSetup s = learn_setup_from_args(args, {"--optimize", "--no-nested", "--force"}, {});
    setup_logging(args);
    warn_if_partial(s.input);
    std::error_code ec;
    if (!std::filesystem::is_directory(s.input, ec)) {
        std::fprintf(stderr,
                     "rollsense report: '%s' is not a dataset folder; the report re-reads trial files for its "
                     "peak plots (record one with 'rollsense run ... --out DIR')\n",
                     s.input.c_str());
        return kExitConfig;
    }
    report::ReportInputs in;
    in.dataset_dir = s.input;
    in.output = output_option(args);
    const auto page = report::report_path(in);
    const auto evaluation = report::evaluation_files_of(page);
    if (int rc = check_output_files("report", s.input, {page, evaluation.text, evaluation.json}); rc != kExitOk)
        return rc;
    // Losing nothing: a run's own evaluation (or an earlier report) is replaced only when asked.
    if (const auto there = existing({page, evaluation.text, evaluation.json}); !there.empty() && !args.flag("--force")) {
        const auto folder = page.parent_path().empty() ? std::filesystem::path(".") : page.parent_path();
        std::fprintf(stderr,
                     "rollsense report: %s already holds %s (the recording run's own evaluation or an earlier "
                     "report); this report would replace them: write it beside them with -o %s (its "
                     "evaluation-NAME.txt/.json beside it), or replace them with --force\n",
                     folder.string().c_str(), there.c_str(), (folder / "report-NAME.html").string().c_str());
        return kExitUsage;
    }
    runtime::PluginRegistry registry(runtime::PluginRegistry::default_search_path(s.plugin_path));
    learn::PipelineResult result;
    if (int rc = run_learning_pipeline("report", args, s, registry, result, false); rc != kExitOk) return rc;
    in.rows = std::move(result.rows);
    in.evaluation = std::move(result.evaluation);
    in.settings = feature_settings_from_args(args);
    in.command_line = "rollsense report " + shell_join(argv);
    auto written = report::write_report(in);
    if (!written) {
        std::fprintf(stderr, "rollsense report: %s\n", written.error().describe().c_str());
        return exit_code_for(written.error().code);
    }
    if (auto st = learn::write_evaluation_files(in.evaluation, evaluation); !st) {
        std::fprintf(stderr, "rollsense report: %s\n", st.error().describe().c_str());
        return exit_code_for(st.code());
    }
    std::printf("\n%s", report::text_summary(in).c_str());
    return kExitOk;
}

const Registration reg{{"report", "evaluate a dataset and write its HTML report (the paper's figures and tables)",
                        learn::with_default_classifier(kHelp, share_dir()), &run}};

}  // namespace
}  // namespace rollsense::cli
