#include "analysis/learn/evaluate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

#include "analysis/learn/checked_classifier.hpp"
#include "analysis/learn/folds.hpp"
#include "analysis/learn/parallel_for.hpp"

namespace rollsense::learn {
namespace {

void say(const EvaluationOptions& o, const std::string& line) {
    if (o.progress) o.progress(line);
}

}  // namespace

Result<RepeatedCv> repeated_cv(const FeatureTable& table, const ClassifierFactory& factory, const ParamSet& params,
                               const FoldPlan& plan, unsigned threads) {
    RepeatedCv r;
    r.folds = plan.folds;
    r.repeats = static_cast<int>(plan.repeats());
    r.confusion = ConfusionMatrix(table.class_names);
    // The repetitions are independent: run them on all cores (a classifier
    // that trains on several threads itself still gains, its serial parts -
    // presorting, prediction - overlap), then combine them in order, so the
    // result is the serial one whatever the thread count.
    std::vector<Result<CvResult>> runs(plan.repeats(), Error{ErrorCode::state_error, "repetition not run"});
    parallel_for(plan.repeats(), threads, [&](std::size_t rep) {
        runs[rep] = cross_validate(table, plan.assignment[rep], plan.folds, factory, params);
    });
    for (std::size_t rep = 0; rep < plan.repeats(); ++rep) {
        auto& cv = runs[rep];
        if (!cv) return Status(cv.error()).with_context("repetition " + std::to_string(rep + 1));
        r.repeat_accuracy.push_back(cv->accuracy());
        r.fold_accuracy.insert(r.fold_accuracy.end(), cv->fold_accuracy.begin(), cv->fold_accuracy.end());
        for (std::size_t i = 0; i < table.rows; ++i) r.confusion.add(table.y[i], cv->predicted[i]);
        if (rep == 0) {
            r.first_predicted = cv->predicted;
            r.first_scores = std::move(cv->scores);
        }
    }
    r.mean = mean(r.repeat_accuracy);
    r.sd = standard_deviation(r.repeat_accuracy);
    r.correct = r.confusion.correct();
    r.total = r.confusion.total();
    // Over the trials: every repetition predicts the same trials again, so its
    // predictions are no new cases (n = R x trials would narrow it sqrt(R)-fold).
    r.wilson = wilson_interval_of_rate(static_cast<double>(r.correct) / static_cast<double>(r.total), table.rows);
    return r;
}

Result<RepeatedCv> repeated_cv(const FeatureTable& table, const ClassifierFactory& factory, const ParamSet& params,
                               int folds, int repeats, std::uint64_t seed, const std::vector<std::string>* groups) {
    auto plan = make_fold_plan(table.y, groups, folds, repeats, seed);
    if (!plan) return plan.error();
    return repeated_cv(table, factory, params, *plan);
}

namespace {

// One classifier of the comparison: the preset on the shared plan, the paper's
// analyses of its first repetition, and with options.optimize the tuning.
Result<EvaluationReport> evaluate_one(const std::vector<features::FeatureRow>& rows, const FeatureTable& table,
                                      const std::vector<std::size_t>& row_of,
                                      const std::vector<std::string>* group_ptr, const FoldPlan& plan,
                                      const std::vector<SchemePlan>& schemes, const ClassifierRequest& request,
                                      const EvaluationOptions& options, bool several, const char* trials_word) {
    const auto& factory = request.factory;
    EvaluationReport rep;
    rep.name = request.name;
    rep.trials = rows.size();
    rep.clean = table.rows;
    rep.classes = table.class_names;
    rep.params = request.params;
    const std::size_t n_rows = table.rows, n_cols = table.cols();
    auto space = options.optimize
                     ? tuning_space(factory, request.params, n_rows, n_cols, options.space, request.name)
                     : declared_search_space(factory, request.params, n_rows, n_cols, options.space);
    // Before minutes of CV: a plugin's error (a space it got wrong, a configure that threw) is said at once either
    // way; another the factory gives (a parameter out of range, say) is left to the CV's first fold, which names it.
    if (!space && (options.optimize || space.error().code == ErrorCode::plugin_error)) return space.error();
    rep.space = space ? std::move(space).value() : SearchSpace{};

    say(options, "cross-validating the preset" + (several ? " of " + request.name : std::string()) + ": " +
                     std::to_string(plan.repeats()) + " x " + std::to_string(plan.folds) + "-fold on " +
                     std::to_string(table.rows) + " " + trials_word + " trials");
    auto base = repeated_cv(table, factory, request.params, plan);
    if (!base) return base.error();
    rep.baseline = std::move(base).value();
    for (const auto& s : schemes) {
        say(options, "cross-validating" + (several ? " " + request.name : std::string()) + ", " +
                         s.scheme.describe() + ": " + std::to_string(s.plan.repeats()) + " x " +
                         std::to_string(s.plan.folds) + "-fold over " + std::to_string(s.groups) + " groups");
        auto cv = repeated_cv(table, factory, request.params, s.plan);
        if (!cv) return Status(cv.error()).with_context(s.scheme.describe());
        rep.scheme_cv.push_back({s.scheme, std::move(cv).value(), std::nullopt, std::nullopt});
    }
    rep.analysis = analyse_like_paper(rows, row_of, table.y, rep.baseline.first_predicted, table.class_names,
                                      options.catalogue);

    if (options.optimize) {
        TuningSetup setup;
        setup.factory = factory;
        setup.params = request.params;
        setup.space = rep.space;
        setup.given_space = options.space;
        setup.classifier = request.name;
        setup.folds = options.folds;
        setup.seed = options.seed;
        setup.bayes = options.bayes;
        setup.say = options.progress;
        // The paper's protocol: one partition, reused for every evaluation and
        // for the reported figure; then nested CV. Random folds tune the random k-fold.
        const TuningFoldRule random{nullptr, group_ptr};
        auto tuned = tune_fixed_partition(table, random, setup);
        if (!tuned) return tuned.error();
        rep.tuned = std::move(tuned).value();
        if (options.nested) {
            auto nested = nested_cv(table, random, setup);
            if (!nested) return nested.error();
            rep.nested = std::move(nested).value();
        }
        // Each grouped / blocked CV tunes on folds of its own kind, so that its
        // tuned figures never profit from the neighbours it holds out.
        for (std::size_t i = 0; i < schemes.size(); ++i) {
            const TuningFoldRule rule{&schemes[i].scheme, &schemes[i].group_of};
            auto& sc = rep.scheme_cv[i];
            auto t = tune_fixed_partition(table, rule, setup);
            if (!t) return Status(t.error()).with_context(sc.scheme.describe());
            sc.tuned = std::move(t).value();
            if (!options.nested) continue;
            auto n = nested_cv(table, rule, setup);
            if (!n) return Status(n.error()).with_context(sc.scheme.describe());
            sc.nested = std::move(n).value();
        }
    }
    return rep;
}

}  // namespace

Result<Evaluation> evaluate_table(const std::vector<features::FeatureRow>& rows, const FeatureTable& table,
                                  const std::vector<std::size_t>& row_of,
                                  const std::vector<ClassifierRequest>& classifiers,
                                  const EvaluationOptions& options) {
    InputTables input;
    input.tables.push_back(table);
    input.kinds.push_back(table.series_length > 0 ? "series" : "features");
    input.row_of = row_of;
    std::vector<ClassifierRequest> requests = classifiers;
    for (auto& r : requests) r.table = 0;
    return evaluate_tables(rows, input, requests, options);
}

Result<Evaluation> evaluate_tables(const std::vector<features::FeatureRow>& rows, const InputTables& input,
                                   const std::vector<ClassifierRequest>& classifiers,
                                   const EvaluationOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    if (classifiers.empty()) return Error{ErrorCode::invalid_argument, "no classifier to evaluate"};
    if (input.tables.empty() || input.kinds.size() != input.tables.size())
        return Error{ErrorCode::invalid_argument, "evaluation: no input table (or tables and kinds differ in number)"};
    const FeatureTable& table = input.tables.front();
    const auto& row_of = input.row_of;
    if (table.rows == 0) return Error{ErrorCode::invalid_argument, "no clean trials to evaluate"};
    if (auto st = check_two_classes(table, "evaluation"); !st) return st.error();
    if (row_of.size() != table.rows)
        return Error{ErrorCode::invalid_argument, "the input table has " + std::to_string(table.rows) +
                                                      " rows but " + std::to_string(row_of.size()) +
                                                      " trial references"};
    for (std::size_t t = 1; t < input.tables.size(); ++t)
        if (input.tables[t].y != table.y || input.tables[t].class_names != table.class_names)
            return Error{ErrorCode::invalid_argument,
                         "the " + input.kinds[t] + " table holds other trials or labels than the " + input.kinds[0] +
                             " table; classifiers compared on the same folds need the same trials in the same order"};
    for (const auto& c : classifiers)
        if (c.table >= input.tables.size())
            return Error{ErrorCode::invalid_argument, "classifier '" + c.name + "' asks for input table " +
                                                          std::to_string(c.table) + " of " +
                                                          std::to_string(input.tables.size())};

    Evaluation ev;
    ev.trials = rows.size();
    ev.clean = table.rows;
    ev.classes = table.class_names;
    ev.truth = table.y;
    ev.selection = input.selection;
    ev.series_time_axis = input.series_time_axis;
    {
        std::vector<bool> kind_used(input.tables.size(), false);
        for (const auto& c : classifiers) kind_used[c.table] = true;
        ev.input.clear();
        for (std::size_t t = 0; t < input.tables.size(); ++t)
            if (kind_used[t]) ev.input += (ev.input.empty() ? "" : "+") + input.kinds[t];
    }
    std::vector<bool> used(rows.size(), false);
    for (std::size_t r : row_of) {
        ev.trial_ids.push_back(rows[r].trial_id);
        ev.peak_clean.push_back(rows[r].clean ? 1 : 0);
        used[r] = true;
    }
    if (!input.refused.empty()) {
        ev.refused = input.refused;
    } else {
        for (std::size_t r = 0; r < rows.size(); ++r)
            if (!used[r])
                ev.refused.push_back({rows[r].trial_id, rows[r].reason.empty() ? "not clean" : rows[r].reason});
    }

    std::vector<std::string> groups;
    const std::vector<std::string>* group_ptr = nullptr;
    if (options.group_of) {
        for (std::size_t r : row_of) groups.push_back(options.group_of(rows[r]));
        group_ptr = &groups;
    }
    // One plan for everyone: the paired comparison is only fair on identical folds.
    auto plan = make_fold_plan(table.y, group_ptr, options.folds, options.repeats, options.seed);
    if (!plan) return plan.error();
    ev.plan = std::move(plan).value();
    for (const auto& scheme : options.schemes) {
        auto scheme_groups_of = scheme_groups(scheme, rows, row_of);
        if (!scheme_groups_of) return scheme_groups_of.error();
        auto p = make_scheme_plan(scheme, table.y, table.class_names, *scheme_groups_of, options.folds,
                                  options.repeats, options.seed);
        if (!p) return p.error();
        const std::set<std::string> distinct(scheme_groups_of->begin(), scheme_groups_of->end());
        ev.schemes.push_back({scheme, std::move(p).value(), distinct.size(), std::move(scheme_groups_of).value()});
    }
    // A scheme's tuning folds that its groups cannot make are refused now, not after the random k-fold's tuning.
    if (options.optimize && options.nested)
        for (const auto& s : ev.schemes)
            if (auto parts = nested_partitions(TuningFoldRule{&s.scheme, &s.group_of}, table.y, table.class_names,
                                               options.folds, options.seed);
                !parts)
                return Status(parts.error()).with_context(s.scheme.describe());

    for (const auto& request : classifiers) {
        const auto one_started = std::chrono::steady_clock::now();
        auto one = evaluate_one(rows, input.tables[request.table], row_of, group_ptr, ev.plan, ev.schemes, request, options,
                                classifiers.size() > 1, used_trials_word(ev));
        if (!one) return in_classifier(one.error(), request.name);
        one->input = input.kinds[request.table];
        one->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - one_started).count();
        ev.classifiers.push_back(std::move(one).value());
    }
    const double ratio = 1.0 / static_cast<double>(std::max(1, options.folds - 1));
    for (std::size_t a = 0; a < ev.classifiers.size(); ++a)
        for (std::size_t b = a + 1; b < ev.classifiers.size(); ++b)
            ev.paired.push_back({a, b,
                                 paired_difference(ev.classifiers[a].baseline.fold_accuracy,
                                                   ev.classifiers[b].baseline.fold_accuracy, ratio)});
    ev.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    // A lone classifier's report covers the whole evaluation, as it always did.
    if (ev.classifiers.size() == 1) ev.classifiers.front().seconds = ev.seconds;
    return ev;
}

Result<Evaluation> evaluate_features(const std::vector<features::FeatureRow>& rows,
                                     const std::vector<ClassifierRequest>& classifiers,
                                     const EvaluationOptions& options) {
    std::vector<std::size_t> row_of;
    const FeatureTable table = features::to_feature_table(rows, &row_of);
    return evaluate_table(rows, table, row_of, classifiers, options);
}

Result<EvaluationReport> evaluate(const std::vector<features::FeatureRow>& rows, const ClassifierFactory& factory,
                                  const EvaluationOptions& options) {
    const std::string name = options.classifier.empty() ? "classifier" : options.classifier;
    auto ev = evaluate_features(rows, {ClassifierRequest{name, factory, options.params}}, options);
    if (!ev) return ev.error();
    return std::move(ev->classifiers.front());
}

Status check_final_tuning(const EvaluationOptions& options) {
    if (!options.optimize || options.schemes.size() <= 1) return {};
    return {ErrorCode::invalid_argument,
            "tuning the model needs one fold scheme for its tuning folds, but " +
                std::to_string(options.schemes.size()) + " are given (" + options.schemes[0].id() + ", " +
                options.schemes[1].id() +
                "); give one (--cv grouped or --cv blocked; rs.analyse: cv = \"grouped\"), see docs/identification.md"};
}

Status check_fold_options(const std::vector<features::FeatureRow>& rows, std::size_t used,
                          const EvaluationOptions& options) {
    if (used < 2) return {};
    if (options.folds > 0 && static_cast<std::size_t>(options.folds) > used) {
        const std::string k = std::to_string(options.folds);
        return {ErrorCode::invalid_argument,
                "--folds " + k + ": " + k + " folds need at least " + k + " trials, and " + std::to_string(used) +
                    " of the " + std::to_string(rows.size()) + " read are used: give --folds " +
                    std::to_string(used) + " or fewer (rs.analyse: folds), or record more trials"};
    }
    for (const auto& scheme : options.schemes)
        if (scheme.kind == CvScheme::Kind::grouped)
            if (auto groups = scheme_groups(scheme, rows, {}); !groups) return groups.error();
    return {};
}

Status check_two_classes(const FeatureTable& table, const char* task) {
    if (table.class_names.size() >= 2) return {};
    return {ErrorCode::invalid_argument,
            std::string(task) + " needs trials of at least two classes (objects); those selected have " +
                (table.class_names.empty() ? std::string("none") : "one, '" + table.class_names.front() + "'") +
                ": record or select trials of two objects or more"};
}

Result<FinalModel> fit_final(const std::vector<features::FeatureRow>& rows, const ClassifierFactory& factory,
                             const EvaluationOptions& options) {
    std::vector<std::size_t> row_of;
    const FeatureTable table = features::to_feature_table(rows, &row_of);
    if (table.rows == 0) return Error{ErrorCode::invalid_argument, "no clean trials to train on"};
    if (auto st = check_two_classes(table, "training"); !st) return st.error();
    FinalModel out;
    out.params = options.params;
    if (options.optimize) {
        // The tuning folds follow the one grouped / blocked scheme asked for
        // (tuning.hpp); without one they are the paper's random stratified folds.
        if (auto st = check_final_tuning(options); !st) return st.error();
        std::vector<std::string> groups;
        TuningFoldRule rule;
        if (!options.schemes.empty()) {
            auto g = scheme_groups(options.schemes.front(), rows, row_of);
            if (!g) return g.error();
            groups = std::move(g).value();
            rule = {&options.schemes.front(), &groups};
        }
        auto space = tuning_space(factory, options.params, table.rows, table.cols(), options.space, options.classifier);
        if (!space) return space.error();
        TuningSetup setup;
        setup.factory = factory;
        setup.params = options.params;
        setup.space = std::move(space).value();
        setup.folds = options.folds;
        setup.seed = options.seed;
        setup.bayes = options.bayes;
        auto s = search_fixed_partition(table, rule, setup);
        if (!s) return s.error();
        out.params = s->search.best_params();
        out.search = std::move(s->search);
        out.tuning_folds = std::to_string(s->folds.k) + "-fold, " + rule.describe();
    }
    auto model = train_classifier(table, factory, out.params);
    if (!model) return model.error();
    out.classifier = std::move(model).value();
    return out;
}

namespace {

std::string format_confusion(const ConfusionMatrix& m) {
    std::string out;
    char buf[64];
    out += "true \\ predicted";
    for (const auto& c : m.classes) {
        std::snprintf(buf, sizeof buf, " %6s", c.c_str());
        out += buf;
    }
    out += "     TPR\n";
    const auto tpr = m.true_positive_rates();
    for (std::size_t i = 0; i < m.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%-16s", m.classes[i].c_str());
        out += buf;
        for (std::size_t j = 0; j < m.size(); ++j) {
            std::snprintf(buf, sizeof buf, " %6zu", m.at(i, j));
            out += buf;
        }
        std::snprintf(buf, sizeof buf, "  %5.1f %%\n", 100.0 * tpr[i]);
        out += buf;
    }
    return out;
}

// " ± 0.9 (sd)" after a mean in percent (without a label: " ± 0.9"), or
// " (one repetition: no spread)".
std::string spread(double sd, const char* label = "sd") {
    if (!has_spread(sd)) return std::string(" (") + no_spread_text + ")";
    char buf[64];
    std::snprintf(buf, sizeof buf, " ± %.1f", 100.0 * sd);
    return label ? buf + std::string(" (") + label + ")" : std::string(buf);
}

// `spread_label`: what the sd is over (repetitions' accuracies, or nested CV's outer folds).
std::string figure(double m, double sd, const Interval& w, std::size_t k, std::size_t n, const char* spread_label = "sd") {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * m);
    std::string out = buf + spread(sd, spread_label);
    std::snprintf(buf, sizeof buf, "   pooled %zu / %zu, 95 %% Wilson over the trials [%.1f, %.1f] %%", k, n,
                  100.0 * w.low, 100.0 * w.high);
    return out + buf;
}

// The figure and choice of a fixed-partition tuning.
std::string tuned_lines(const TunedCv& t, const SearchSpace& space) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "  accuracy %.1f %%  -- tuned and scored on the same folds: optimistic\n",
                  100.0 * t.same_folds_accuracy);
    return buf + ("  chosen: " + describe_params(t.search.best_params(), space) + "\n");
}

// A nested CV's figure and each outer fold's accuracy and choice.
std::string nested_lines(const NestedCv& n, const SearchSpace& space) {
    std::string out = "  accuracy " + figure(n.mean, n.sd, n.wilson, n.correct, n.total, "sd over the outer folds") + "\n";
    char buf[64];
    for (std::size_t i = 0; i < n.chosen.size(); ++i) {
        std::snprintf(buf, sizeof buf, "  outer fold %zu: %.1f %%  ", i + 1, 100.0 * n.outer_accuracy[i]);
        out += buf + describe_params(n.chosen[i], space) + "\n";
    }
    return out;
}

}  // namespace

std::string format_report(const EvaluationReport& r, bool with_timing) {
    std::string out;
    char buf[256];
    std::snprintf(buf, sizeof buf, "trials %zu, clean %zu, classes %zu\n\n", r.trials, r.clean, r.classes.size());
    out += buf;
    const auto& b = r.baseline;
    std::snprintf(buf, sizeof buf, "preset, %d x repeated stratified %d-fold CV:\n  accuracy ", b.repeats, b.folds);
    out += buf;
    out += figure(b.mean, b.sd, b.wilson, b.correct, b.total) + "\n";
    if (!r.params.values().empty()) out += "  parameters: " + describe_param_values(r.params) + "\n";
    for (const auto& s : r.scheme_cv) {
        std::snprintf(buf, sizeof buf, "%s, %d x %d-fold CV (whole groups held out):\n  accuracy ",
                      s.scheme.describe().c_str(), s.cv.repeats, s.cv.folds);
        out += buf + figure(s.cv.mean, s.cv.sd, s.cv.wilson, s.cv.correct, s.cv.total) + "\n";
        if (s.tuned) {
            std::snprintf(buf, sizeof buf,
                          "  Bayesian optimisation, %zu evaluations on ONE fixed partition of this scheme "
                          "(tuning folds %s too):\n",
                          s.tuned->search.history.size(), s.scheme.describe().c_str());
            out += buf + tuned_lines(*s.tuned, r.space);
        }
        if (s.nested)
            out += "  nested CV, outer and tuning folds " + s.scheme.describe() +
                   " (tuning folds from each outer training fold's trials only): the honest tuned figure\n" +
                   nested_lines(*s.nested, r.space);
    }
    out += "\nconfusion matrix (pooled over repetitions):\n" + format_confusion(b.confusion);
    if (r.tuned) {
        const auto& t = *r.tuned;
        std::snprintf(buf, sizeof buf,
                      "\nBayesian optimisation, %zu evaluations on ONE fixed %d-fold partition (the paper's protocol):\n",
                      t.search.history.size(), b.folds);
        out += buf + tuned_lines(t, r.space);
    }
    if (r.nested)
        out += "nested CV (tuning inside each outer training fold): the honest tuned figure\n" +
               nested_lines(*r.nested, r.space);
    out += "\nthe paper's analyses (preset, first repetition = one " + std::to_string(b.folds) +
           "-fold CV) beside the paper:\n";
    out += format_paper_comparison(r.analysis);
    if (with_timing) {
        std::snprintf(buf, sizeof buf, "\nevaluation took %.1f s\n", r.seconds);
        out += buf;
    }
    return out;
}

SubsetScore paper_refused_first_repeat(const Evaluation& ev, const EvaluationReport& c) {
    SubsetScore s;
    const auto& p = c.baseline.first_predicted;
    for (std::size_t i = 0; i < ev.peak_clean.size() && i < p.size(); ++i)
        if (!ev.peak_clean[i]) {
            ++s.total;
            s.correct += p[i] == ev.truth[i];
        }
    return s;
}

std::string selection_line(const Evaluation& ev) {
    if (ev.input.find("series") == std::string::npos) return {};
    char buf[256];
    std::snprintf(buf, sizeof buf, "trials: %s (%zu used, %zu left out; reasons in evaluation.json)\n",
                  ev.selection == "paper_clean"
                      ? "the paper's clean trials that the series rule also accepts"
                      : "every trial the series rule accepts, the paper's refused ones included",
                  ev.clean, ev.refused.size());
    std::string out = buf;
    for (const auto& c : ev.classifiers) {
        const auto k = paper_refused_first_repeat(ev, c);
        if (k.total == 0) continue;
        std::snprintf(buf, sizeof buf,
                      "  %s on the %zu trials the paper's peak rule refuses: %zu right (%.1f %%, out-of-fold, first "
                      "repetition)\n",
                      c.name.c_str(), k.total, k.correct, 100.0 * static_cast<double>(k.correct) / static_cast<double>(k.total));
        out += buf;
    }
    return out;
}

std::string time_axis_caveat(const Evaluation& ev) {
    if (ev.series_time_axis.empty() || ev.series_time_axis == "contact") return {};
    return "series time axis " + ev.series_time_axis + ": " + kOutsideTimingRule +
           " (the whole recording is resampled, so the traversal speed, and with it a cylinder's diameter and the "
           "speed setting, is in the series); for comparison only, docs/series-preparation.md";
}

namespace {
std::string format_evaluation_body(const Evaluation& ev);
}  // namespace

std::string format_evaluation(const Evaluation& ev) {
    const std::string caveat = time_axis_caveat(ev);
    return (caveat.empty() ? std::string() : "NOTE: " + caveat + "\n\n") + format_evaluation_body(ev);
}

const char* used_trials_word(const Evaluation& evaluation) {
    return evaluation.selection == "series_accepted" ? "used" : "clean";
}

namespace {
// Everything after the caveat.
std::string format_evaluation_body(const Evaluation& ev) {
    if (ev.classifiers.size() == 1) {
        std::string report = format_report(ev.primary());  // its first line, "trials N, clean M, ...", with the word
        if (const auto at = report.find(", clean "); at < report.find('\n'))
            report.replace(at + 2, 5, used_trials_word(ev));
        return report + selection_line(ev) + (ev.prefixes ? format_prefix_curves(*ev.prefixes) : std::string());
    }
    std::string out;
    char buf[256];
    std::snprintf(buf, sizeof buf, "trials %zu, %s %zu, classes %zu\n\n", ev.trials, used_trials_word(ev), ev.clean,
                  ev.classes.size());
    out += buf;
    std::size_t width = 10;
    for (const auto& c : ev.classifiers) width = std::max(width, c.name.size());
    const int w = static_cast<int>(width);
    std::snprintf(buf, sizeof buf, "%zu classifiers on the same %zu x %s %d-fold partitions (seeds %llu..%llu):\n",
                  ev.classifiers.size(), ev.plan.repeats(), ev.plan.grouped ? "grouped" : "stratified",
                  ev.plan.folds, static_cast<unsigned long long>(ev.plan.seeds.front()),
                  static_cast<unsigned long long>(ev.plan.seeds.back()));
    out += buf;
    for (const auto& c : ev.classifiers) {
        std::snprintf(buf, sizeof buf, "  %-*s  %5.1f %%", w, c.name.c_str(), 100.0 * c.baseline.mean);
        out += buf + spread(c.baseline.sd, "sd over repetitions") +
               (ev.input.find('+') != std::string::npos ? "   input: " + c.input : std::string()) + "\n";
        for (const auto& s : c.scheme_cv) {
            std::snprintf(buf, sizeof buf, "  %-*s  %5.1f %%", w, "", 100.0 * s.cv.mean);
            out += buf + spread(s.cv.sd, nullptr) + " " + s.scheme.describe() + "\n";
        }
    }
    out += selection_line(ev);
    out += "\npaired per-fold accuracy differences (a − b, every fold of every repetition; t: paired t, df = n − 1;\n"
           "t corrected: Nadeau-Bengio, which allows for folds sharing training trials; a/b/ties: sign counts):\n";
    for (const auto& p : ev.paired) {
        const auto& d = p.difference;
        std::snprintf(buf, sizeof buf,
                      "  %s − %s: mean %+.2f points, sd %.2f, n %zu, t %.2f, t corrected %.2f, a/b/ties %zu/%zu/%zu\n",
                      ev.classifiers[p.a].name.c_str(), ev.classifiers[p.b].name.c_str(), 100.0 * d.mean,
                      100.0 * d.sd, d.n(), d.t, d.t_corrected, d.a_better, d.b_better, d.ties);
        out += buf;
    }
    for (const auto& c : ev.classifiers) out += "\n==== " + c.name + " ====\n" + format_report(c, false);
    if (ev.prefixes) out += format_prefix_curves(*ev.prefixes);
    std::snprintf(buf, sizeof buf, "\nevaluation took %.1f s\n", ev.seconds);
    out += buf;
    return out;
}
}  // namespace

}  // namespace rollsense::learn
