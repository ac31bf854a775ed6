#include "analysis/learn/evaluate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

#include "analysis/learn/folds.hpp"
#include "analysis/learn/parallel_for.hpp"

namespace rollsense::learn {
namespace {

void say(const EvaluationOptions& o, const std::string& line) {
    if (o.progress) o.progress(line);
}

std::string pct(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * v);
    return buf;
}

Result<std::vector<int>> make_folds(std::span<const int> labels, const std::vector<std::string>* groups, int k,
                                    std::uint64_t seed) {
    if (groups) return grouped_folds(*groups, labels, k, seed);
    return stratified_folds(labels, k, seed);
}

// Objective of the optimiser: k-fold misclassification rate on one partition.
Objective cv_error(const FeatureTable& table, const std::vector<int>& folds, int k, const ClassifierFactory& factory) {
    return [&table, &folds, k, &factory](const ParamSet& p) -> Result<double> {
        auto cv = cross_validate(table, folds, k, factory, p);
        if (!cv) return cv.error();
        return 1.0 - cv->accuracy();
    };
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
                                      const EvaluationOptions& options, bool several) {
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
    if (!space && options.optimize) return space.error();  // before minutes of CV
    rep.space = space ? std::move(space).value() : SearchSpace{};  // else the CV below reports the factory's error
    const std::vector<std::string> no_groups;
    const std::vector<std::string>& groups = group_ptr ? *group_ptr : no_groups;

    say(options, "cross-validating the preset" + (several ? " of " + request.name : std::string()) + ": " +
                     std::to_string(plan.repeats()) + " x " + std::to_string(plan.folds) + "-fold on " +
                     std::to_string(table.rows) + " clean trials");
    auto base = repeated_cv(table, factory, request.params, plan);
    if (!base) return base.error();
    rep.baseline = std::move(base).value();
    for (const auto& s : schemes) {
        say(options, "cross-validating" + (several ? " " + request.name : std::string()) + ", " +
                         s.scheme.describe() + ": " + std::to_string(s.plan.repeats()) + " x " +
                         std::to_string(s.plan.folds) + "-fold over " + std::to_string(s.groups) + " groups");
        auto cv = repeated_cv(table, factory, request.params, s.plan);
        if (!cv) return Status(cv.error()).with_context(s.scheme.describe());
        rep.scheme_cv.push_back({s.scheme, std::move(cv).value()});
    }
    rep.analysis = analyse_like_paper(rows, row_of, table.y, rep.baseline.first_predicted, table.class_names,
                                      options.catalogue);

    if (options.optimize) {
        // The paper's protocol: one partition, reused for every evaluation and
        // for the reported figure.
        auto fixed = make_folds(table.y, group_ptr, options.folds, options.seed);
        if (!fixed) return fixed.error();
        BayesOptOptions bo = options.bayes;
        bo.seed = options.seed;
        if (!bo.progress && options.progress)
            bo.progress = [&](int i, const ParamSet& p, double v) {
                say(options, "  optimiser " + std::to_string(i) + ": error " + pct(v) + "  " +
                                 describe_params(p, rep.space));
            };
        say(options, "Bayesian optimisation on one fixed partition (" + std::to_string(bo.evaluations) +
                         " evaluations)");
        auto search = bayes_optimize(rep.space, cv_error(table, *fixed, options.folds, factory), request.params, bo);
        if (!search) return search.error();
        TunedCv tuned;
        tuned.search = std::move(search).value();
        auto cv = cross_validate(table, *fixed, options.folds, factory, tuned.search.best_params());
        if (!cv) return cv.error();
        tuned.same_folds_accuracy = cv->accuracy();
        tuned.confusion = confusion(table.y, cv->predicted, table.class_names);
        rep.tuned = std::move(tuned);

        if (options.nested) {
            auto outer = make_folds(table.y, group_ptr, options.folds, options.seed + 7919);
            if (!outer) return outer.error();
            NestedCv nested;
            nested.confusion = ConfusionMatrix(table.class_names);
            for (int f = 0; f < options.folds; ++f) {
                const auto train_rows = fold_rows(*outer, f, false);
                const auto test_rows = fold_rows(*outer, f, true);
                if (test_rows.empty()) continue;
                const FeatureTable inner_table = subset(table, train_rows);
                std::vector<std::string> inner_groups;
                for (std::size_t r : train_rows)
                    if (group_ptr) inner_groups.push_back(groups[r]);
                auto inner = make_folds(inner_table.y, group_ptr ? &inner_groups : nullptr, options.folds,
                                        options.seed + 104729 + static_cast<std::uint64_t>(f));
                if (!inner) return inner.error();
                BayesOptOptions ibo = options.bayes;
                ibo.seed = options.seed + 31 * static_cast<std::uint64_t>(f + 1);
                ibo.progress = nullptr;
                say(options, "nested CV: tuning inside outer fold " + std::to_string(f + 1) + " of " +
                                 std::to_string(options.folds));
                auto inner_space = tuning_space(factory, request.params, inner_table.rows, inner_table.cols(),
                                                options.space, request.name);
                if (!inner_space) return inner_space.error();
                auto s = bayes_optimize(*inner_space, cv_error(inner_table, *inner, options.folds, factory),
                                        request.params, ibo);
                if (!s) return Status(s.error()).with_context("nested CV outer fold " + std::to_string(f + 1));
                auto model = train_classifier(inner_table, factory, s->best_params());
                if (!model) return model.error();
                auto labels = predict_labels(**model, table, test_rows);
                if (!labels) return labels.error();
                std::size_t ok = 0;
                for (std::size_t i = 0; i < test_rows.size(); ++i) {
                    nested.confusion.add(table.y[test_rows[i]], (*labels)[i]);
                    ok += (*labels)[i] == table.y[test_rows[i]];
                }
                nested.outer_accuracy.push_back(static_cast<double>(ok) / static_cast<double>(test_rows.size()));
                nested.chosen.push_back(s->best_params());
            }
            nested.mean = mean(nested.outer_accuracy);
            nested.sd = standard_deviation(nested.outer_accuracy);
            nested.correct = nested.confusion.correct();
            nested.total = nested.confusion.total();
            nested.wilson = wilson_interval(nested.correct, nested.total);
            rep.nested = std::move(nested);
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
    if (table.class_names.size() < 2)
        return Error{ErrorCode::invalid_argument, "evaluation needs at least two classes among the clean trials"};
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
        ev.schemes.push_back({scheme, std::move(p).value(), distinct.size()});
    }

    for (const auto& request : classifiers) {
        const auto one_started = std::chrono::steady_clock::now();
        auto one = evaluate_one(rows, input.tables[request.table], row_of, group_ptr, ev.plan, ev.schemes, request, options,
                                classifiers.size() > 1);
        if (!one) return Status(one.error()).with_context("classifier '" + request.name + "'");
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

Result<FinalModel> fit_final(const std::vector<features::FeatureRow>& rows, const ClassifierFactory& factory,
                             const EvaluationOptions& options) {
    const FeatureTable table = features::to_feature_table(rows);
    if (table.rows == 0) return Error{ErrorCode::invalid_argument, "no clean trials to train on"};
    FinalModel out;
    out.params = options.params;
    if (options.optimize) {
        auto fixed = stratified_folds(table.y, options.folds, options.seed);
        if (!fixed) return fixed.error();
        auto space = tuning_space(factory, options.params, table.rows, table.cols(), options.space, options.classifier);
        if (!space) return space.error();
        BayesOptOptions bo = options.bayes;
        bo.seed = options.seed;
        auto s = bayes_optimize(*space, cv_error(table, *fixed, options.folds, factory), options.params, bo);
        if (!s) return s.error();
        out.params = s->best_params();
        out.search = std::move(s).value();
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
    }
    out += "\nconfusion matrix (pooled over repetitions):\n" + format_confusion(b.confusion);
    if (r.tuned) {
        const auto& t = *r.tuned;
        std::snprintf(buf, sizeof buf,
                      "\nBayesian optimisation, %zu evaluations on ONE fixed %d-fold partition (the paper's protocol):\n"
                      "  accuracy %.1f %%  -- tuned and scored on the same folds: optimistic\n",
                      t.search.history.size(), b.folds, 100.0 * t.same_folds_accuracy);
        out += buf;
        out += "  chosen: " + describe_params(t.search.best_params(), r.space) + "\n";
    }
    if (r.nested) {
        const auto& n = *r.nested;
        out += "nested CV (tuning inside each outer training fold): the honest tuned figure\n  accuracy ";
        out += figure(n.mean, n.sd, n.wilson, n.correct, n.total, "sd over the outer folds") + "\n";
        for (std::size_t i = 0; i < n.chosen.size(); ++i) {
            std::snprintf(buf, sizeof buf, "  outer fold %zu: %.1f %%  ", i + 1, 100.0 * n.outer_accuracy[i]);
            out += buf + describe_params(n.chosen[i], r.space) + "\n";
        }
    }
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

namespace {
// With a series classifier, which trials were used (features alone: the
// paper's clean trials, as the report always said).
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
}  // namespace

std::string format_evaluation(const Evaluation& ev) {
    if (ev.classifiers.size() == 1)
        return format_report(ev.primary()) + selection_line(ev) +
               (ev.prefixes ? format_prefix_curves(*ev.prefixes) : std::string());
    std::string out;
    char buf[256];
    std::snprintf(buf, sizeof buf, "trials %zu, clean %zu, classes %zu\n\n", ev.trials, ev.clean, ev.classes.size());
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

}  // namespace rollsense::learn
