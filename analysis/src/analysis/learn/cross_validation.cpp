#include "analysis/learn/cross_validation.hpp"

#include "analysis/learn/checked_classifier.hpp"
#include "analysis/learn/folds.hpp"

namespace rollsense::learn {

FeatureTable subset(const FeatureTable& table, std::span<const std::size_t> rows) {
    FeatureTable t;
    t.feature_names = table.feature_names;
    t.channel_names = table.channel_names;  // a series table stays one (series_length > 0)
    t.series_length = table.series_length;
    t.class_names = table.class_names;
    t.rows = rows.size();
    t.x.reserve(rows.size() * table.cols());
    t.y.reserve(rows.size());
    for (std::size_t r : rows) {
        const auto row = table.row(r);
        t.x.insert(t.x.end(), row.begin(), row.end());
        t.y.push_back(table.y[r]);
    }
    return t;
}

Result<ClassifierPtr> train_classifier(const FeatureTable& table, const ClassifierFactory& factory,
                                       const ParamSet& params) {
    auto made = factory(params);
    if (!made) return made.error();
    ClassifierPtr c = std::move(made).value();
    if (auto s = c->train(table); !s) return s;
    return c;
}

Result<std::vector<Prediction>> predict_rows(const Classifier& c, const FeatureTable& table,
                                             std::span<const std::size_t> rows) {
    std::vector<Prediction> out;
    out.reserve(rows.size());
    for (std::size_t r : rows) {
        auto p = c.predict(table.row(r));
        if (!p) return p.error();
        // Plugins are checked as they predict (checked_classifier); this
        // guards the confusion matrix against any classifier.
        if (auto s = check_prediction(*p, table.class_names, "classifier"); !s) return s.error();
        out.push_back(std::move(p).value());
    }
    return out;
}

Result<std::vector<int>> predict_labels(const Classifier& c, const FeatureTable& table,
                                        std::span<const std::size_t> rows) {
    auto predictions = predict_rows(c, table, rows);
    if (!predictions) return predictions.error();
    std::vector<int> out;
    out.reserve(predictions->size());
    for (const auto& p : *predictions) out.push_back(p.label);
    return out;
}

Result<CvResult> cross_validate(const FeatureTable& table, std::span<const int> folds, int k,
                                const ClassifierFactory& factory, const ParamSet& params) {
    if (folds.size() != table.rows)
        return Error{ErrorCode::invalid_argument, "fold assignment has " + std::to_string(folds.size()) +
                                                      " rows, the table " + std::to_string(table.rows)};
    CvResult r;
    r.predicted.assign(table.rows, -1);
    r.scores.assign(table.rows, {});
    for (int f = 0; f < k; ++f) {
        const auto train_rows = fold_rows(folds, f, false);
        const auto test_rows = fold_rows(folds, f, true);
        if (test_rows.empty()) continue;
        auto model = train_classifier(subset(table, train_rows), factory, params);
        if (!model) return Status(model.error()).with_context("fold " + std::to_string(f + 1));
        auto predictions = predict_rows(**model, table, test_rows);
        if (!predictions) return Status(predictions.error()).with_context("fold " + std::to_string(f + 1));
        std::size_t ok = 0;
        for (std::size_t i = 0; i < test_rows.size(); ++i) {
            auto& p = (*predictions)[i];
            r.predicted[test_rows[i]] = p.label;
            ok += p.label == table.y[test_rows[i]];
            r.scores[test_rows[i]] = std::move(p.scores);
        }
        r.correct += ok;
        r.fold_accuracy.push_back(static_cast<double>(ok) / static_cast<double>(test_rows.size()));
    }
    return r;
}

}  // namespace rollsense::learn
