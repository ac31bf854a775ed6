#include "analysis/learn/tuning.hpp"

#include <cstdio>

#include "analysis/learn/folds.hpp"

namespace rollsense::learn {

std::string TuningFoldRule::describe() const {
    if (scheme) return scheme->describe();
    return groups ? "random grouped" : "random stratified";
}

Result<TuningFolds> tuning_folds(const TuningFoldRule& rule, std::span<const int> labels,
                                 const std::vector<std::string>& class_names, std::span<const std::size_t> rows, int k,
                                 std::uint64_t seed) {
    if (rule.scheme && !rule.groups)
        return Error{ErrorCode::invalid_argument, "tuning folds " + rule.scheme->describe() + ": no groups given"};
    std::vector<int> sub_labels;
    std::vector<std::string> sub_groups;
    for (std::size_t r : rows) {
        sub_labels.push_back(labels[r]);
        if (rule.groups) sub_groups.push_back((*rule.groups)[r]);
    }
    TuningFolds out;
    if (rule.scheme) {
        auto plan = make_scheme_plan(*rule.scheme, sub_labels, class_names, sub_groups, k, 1, seed);
        if (!plan) return plan.error();
        out.k = plan->folds;
        out.fold = std::move(plan->assignment.front());
        return out;
    }
    auto f = rule.groups ? grouped_folds(sub_groups, sub_labels, k, seed) : stratified_folds(sub_labels, k, seed);
    if (!f) return f.error();
    out.k = k;
    out.fold = std::move(f).value();
    return out;
}

namespace {

void say(const TuningSetup& s, const std::string& line) {
    if (s.say) s.say(line);
}

std::vector<std::size_t> all_rows(std::size_t n) {
    std::vector<std::size_t> rows(n);
    for (std::size_t i = 0; i < n; ++i) rows[i] = i;
    return rows;
}

// ", grouped by speed" after a progress line's subject; nothing for random
// folds, whose lines read as they always did.
std::string scheme_suffix(const TuningFoldRule& rule) { return rule.scheme ? ", " + rule.scheme->describe() : ""; }

}  // namespace

Objective tuning_objective(const FeatureTable& table, const TuningFolds& folds, const ClassifierFactory& factory) {
    return [&table, &folds, &factory](const ParamSet& p) -> Result<double> {
        auto cv = cross_validate(table, folds.fold, folds.k, factory, p);
        if (!cv) return cv.error();
        return 1.0 - cv->accuracy();
    };
}

Result<FixedSearch> search_fixed_partition(const FeatureTable& table, const TuningFoldRule& rule,
                                           const TuningSetup& setup) {
    auto fixed = tuning_folds(rule, table.y, table.class_names, all_rows(table.rows), setup.folds, setup.seed);
    if (!fixed) return Status(fixed.error()).with_context("the optimiser's partition");
    BayesOptOptions bo = setup.bayes;
    bo.seed = setup.seed;
    if (!bo.progress && setup.say)
        bo.progress = [&setup](int i, const ParamSet& p, double v) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * v);
            say(setup, "  optimiser " + std::to_string(i) + ": error " + buf + "  " + describe_params(p, setup.space));
        };
    say(setup, "Bayesian optimisation on one fixed partition" + scheme_suffix(rule) + " (" +
                   std::to_string(bo.evaluations) + " evaluations)");
    auto search = bayes_optimize(setup.space, tuning_objective(table, *fixed, setup.factory), setup.params, bo);
    if (!search) return search.error();
    return FixedSearch{std::move(fixed).value(), std::move(search).value()};
}

Result<TunedCv> tune_fixed_partition(const FeatureTable& table, const TuningFoldRule& rule, const TuningSetup& setup) {
    auto fixed = search_fixed_partition(table, rule, setup);
    if (!fixed) return fixed.error();
    TunedCv tuned;
    tuned.search = std::move(fixed->search);
    auto cv = cross_validate(table, fixed->folds.fold, fixed->folds.k, setup.factory, tuned.search.best_params());
    if (!cv) return cv.error();
    tuned.same_folds_accuracy = cv->accuracy();
    tuned.confusion = confusion(table.y, cv->predicted, table.class_names);
    return tuned;
}

Result<NestedPartitions> nested_partitions(const TuningFoldRule& rule, std::span<const int> labels,
                                           const std::vector<std::string>& class_names, int k, std::uint64_t seed) {
    NestedPartitions out;
    auto outer = tuning_folds(rule, labels, class_names, all_rows(labels.size()), k, seed + 7919);
    if (!outer) return Status(outer.error()).with_context("nested CV's outer folds");
    out.outer = std::move(outer).value();
    for (int f = 0; f < out.outer.k; ++f) {
        const auto train_rows = fold_rows(out.outer.fold, f, false);
        // The tuning folds of this outer training fold: its trials only, by the same rule.
        auto inner = tuning_folds(rule, labels, class_names, train_rows, k,
                                  seed + 104729 + static_cast<std::uint64_t>(f));
        if (!inner)
            return Status(inner.error()).with_context("nested CV outer fold " + std::to_string(f + 1) +
                                                      ": its tuning folds (" + rule.describe() +
                                                      ", from its training trials only)");
        out.inner.push_back(std::move(inner).value());
    }
    return out;
}

Result<NestedCv> nested_cv(const FeatureTable& table, const TuningFoldRule& rule, const TuningSetup& setup) {
    auto parts = nested_partitions(rule, table.y, table.class_names, setup.folds, setup.seed);
    if (!parts) return parts.error();
    const TuningFolds& outer = parts->outer;
    NestedCv nested;
    nested.confusion = ConfusionMatrix(table.class_names);
    for (int f = 0; f < outer.k; ++f) {
        const auto train_rows = fold_rows(outer.fold, f, false);
        const auto test_rows = fold_rows(outer.fold, f, true);
        if (test_rows.empty()) continue;
        const std::string where = "nested CV outer fold " + std::to_string(f + 1);
        const FeatureTable inner_table = subset(table, train_rows);
        const TuningFolds& inner = parts->inner[static_cast<std::size_t>(f)];
        BayesOptOptions ibo = setup.bayes;
        ibo.seed = setup.seed + 31 * static_cast<std::uint64_t>(f + 1);
        ibo.progress = nullptr;
        say(setup, "nested CV" + scheme_suffix(rule) + ": tuning inside outer fold " + std::to_string(f + 1) + " of " +
                       std::to_string(outer.k));
        auto inner_space = tuning_space(setup.factory, setup.params, inner_table.rows, inner_table.cols(),
                                        setup.given_space, setup.classifier);
        if (!inner_space) return inner_space.error();
        auto s = bayes_optimize(*inner_space, tuning_objective(inner_table, inner, setup.factory), setup.params, ibo);
        if (!s) return Status(s.error()).with_context(where);
        auto model = train_classifier(inner_table, setup.factory, s->best_params());
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
    return nested;
}

}  // namespace rollsense::learn
