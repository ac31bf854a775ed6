// rollsense train INPUT -o MODEL: fit the classifier on every clean trial and
// save its model for live identification.
#include <cstdio>
#include <string>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "cli/output_paths.hpp"
#include "cli/partial_dataset.hpp"
#include "cli/paths.hpp"
#include "analysis/learn/defaults.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/inputs.hpp"
#include "analysis/learn/pipeline.hpp"
#include "analysis/learn/plugin_factory.hpp"

namespace rollsense::cli {

using LearnSetup = learn::CommandSetup;
LearnSetup learn_setup_from_args(const Args& args, const std::vector<std::string>& extra_flags,
                                 const std::vector<std::string>& not_taken);  // cmd_evaluate.cpp
void require_optimize(const Args& args, const std::vector<std::string>& options);  // cmd_evaluate.cpp
int prepare(const char* command, const Args& args, const LearnSetup& s, runtime::PluginRegistry& registry,
            std::vector<features::FeatureRow>& rows, learn::PreparedClassifier& classifier,
            learn::InputOptions& inputs);  // cmd_evaluate.cpp

namespace {

const char* kHelp = R"(usage: rollsense train INPUT -o MODEL [options]

Train the classifier on every clean trial of INPUT (a dataset folder or a
features CSV) and save its model. With --optimize the parameters are chosen
first by the paper's protocol (Bayesian optimisation, 5-fold CV on one fixed
partition); run 'rollsense evaluate --optimize' for an honest figure of that.

A classifier that takes the prepared series (minirocket) is trained on the
dataset's three sensor channels prepared by the series rule
(docs/series-preparation.md), on the trials 'rollsense evaluate' would use:
the same model rs.analyse saves with the same options. The model file records
the series rule's settings (--series-amplitude and the rest), so that
'rollsense predict' and clf:identify() prepare as training did. It needs a
dataset folder (a features CSV has no series) and takes no --optimize.

options:
  -o, --output MODEL  model file to write (required; - for stdout)
  --classifier NAME   classifier plugin ({default_classifier})
  --set KEY=VALUE     classifier parameter, repeatable
  --optimize          choose the parameters by Bayesian optimisation
  --evaluations N     with --optimize: optimiser evaluations (30)
  --folds K, --seed S with --optimize: partition of the optimiser's CV (5; the
                      seed the dataset was recorded with, else 1)
  --cv SCHEME, --group-by COLUMN, --block N
                      with --optimize: the optimiser's folds hold out whole
                      groups, as 'rollsense evaluate --cv' (one scheme:
                      grouped or blocked); default: random stratified folds
                      (the paper's). The folds used are printed
  --trials SET        clean (default): the paper's clean trials, with a
                      series classifier only those the series rule accepts
                      too; all: every trial the series rule accepts (series
                      classifiers only), as 'rollsense evaluate --help' says
  --series-amplitude MODE
                      series rule amplitude: global_scale or z_per_channel
                      (default: docs/series-preparation.md; series
                      classifiers only)
  --plugin-path DIR   search classifier plugins here first (repeatable)
  -v, --verbose       debug messages;   -q, --quiet   no info messages: warnings, errors
  plus the feature options of 'rollsense features' when INPUT is a dataset
  (refused with a features CSV, whose features are computed already))";

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    // One model on every clean trial: no repetitions, and no partition unless the optimiser's.
    const LearnSetup s = learn_setup_from_args(args, {"--optimize"}, {"--repeats", "--series-time-axis"});
    require_optimize(args, {"--folds", "--seed"});
    setup_logging(args);
    warn_if_partial(s.input);
    const std::string out = output_option(args);
    if (out.empty()) throw UsageError("-o MODEL is required: where to save the trained model");
    if (int rc = check_output_files("train", s.input, {out}); rc != kExitOk) return rc;
    runtime::PluginRegistry registry(runtime::PluginRegistry::default_search_path(s.plugin_path));
    std::vector<features::FeatureRow> rows;
    learn::PreparedClassifier classifier;
    learn::InputOptions inputs;
    if (int rc = prepare("train", args, s, registry, rows, classifier, inputs); rc != kExitOk) return rc;
    learn::EvaluationOptions o = s.options;
    const auto& factory = classifier.factory;
    if (o.optimize) {  // a feature classifier (prepare refused tuning a series one)
        // The space the classifier declares for this data, so the progress
        // lines name exactly the searched parameters.
        const FeatureTable table = features::to_feature_table(rows);
        // --folds or --group-by that the trials cannot take: the command line's error, before any tuning.
        if (auto st = learn::check_fold_options(rows, table.rows, o); !st) {
            std::fprintf(stderr, "rollsense train: %s\n", st.error().describe().c_str());
            return kExitUsage;
        }
        auto space = learn::tuning_space(factory, o.params, table.rows, table.cols(), o.space, s.classifier);
        if (!space) {
            std::fprintf(stderr, "rollsense train: %s\n", space.error().describe().c_str());
            return kExitConfig;
        }
        o.bayes.progress = [space = *space](int i, const ParamSet& p, double v) {
            std::fprintf(stderr, "optimiser %d: error %.1f %%  %s\n", i, 100.0 * v,
                         learn::describe_params(p, space).c_str());
        };
    }
    auto model = learn::fit_final_prepared(rows, s.input, classifier, o, inputs);
    if (!model) {
        std::fprintf(stderr, "rollsense train: %s\n", model.error().describe().c_str());
        return exit_code_for(model.error().code);
    }
    if (auto st = model->classifier->save(out); !st) {
        std::fprintf(stderr, "rollsense train: %s\n", st.error().describe().c_str());
        return exit_code_for(st.code());
    }
    // On stderr, as every command's account of its work: stdout carries results only (the model, with -o /dev/stdout).
    if (!model->tuning_folds.empty()) std::fprintf(stderr, "tuning folds: %s\n", model->tuning_folds.c_str());
    const std::string params = learn::describe_param_values(model->params);
    std::fprintf(stderr, "trained '%s' on %zu classes%s%s\nwrote %s\n", s.classifier.c_str(),
                model->classifier->class_names().size(), params.empty() ? "" : ", parameters: ", params.c_str(),
                out.c_str());
    return kExitOk;
}

const Registration reg{{"train", "train a classifier on a dataset or features file and save the model",
                        learn::with_default_classifier(kHelp, share_dir()), &run}};

}  // namespace
}  // namespace rollsense::cli
