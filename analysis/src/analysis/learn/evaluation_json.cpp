#include "analysis/learn/evaluation_json.hpp"

#include <optional>
#include <type_traits>

#include "analysis/learn/json_writer.hpp"

namespace rollsense::learn {
namespace {

void write_param(JsonWriter& w, const ParamValue& v) {
    std::visit(
        [&w](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::int64_t> || std::is_same_v<T, double> ||
                          std::is_same_v<T, std::string>) {
                w.value(x);
            } else {
                w.begin_array();
                for (const auto& e : x) w.value(e);
                w.end_array();
            }
        },
        v);
}

void write_params(JsonWriter& w, const ParamSet& params) {
    w.begin_object();
    for (const auto& [k, v] : params.values()) {
        w.key(k);
        write_param(w, v);
    }
    w.end_object();
}

void write_numbers(JsonWriter& w, const std::vector<double>& v) {
    w.begin_array();
    for (double x : v) w.value(x);
    w.end_array();
}

void write_confusion(JsonWriter& w, const ConfusionMatrix& m) {
    w.begin_array();
    for (std::size_t i = 0; i < m.size(); ++i) {
        w.begin_array();
        for (std::size_t j = 0; j < m.size(); ++j) w.value(static_cast<std::uint64_t>(m.at(i, j)));
        w.end_array();
    }
    w.end_array();
}

// "assignment": per repetition, the test fold of every trial (in folds.trials order).
void write_assignment(JsonWriter& w, const FoldPlan& plan) {
    w.key("assignment").begin_array();
    for (const auto& a : plan.assignment) {
        w.begin_array();
        for (int f : a) w.value(f);
        w.end_array();
    }
    w.end_array();
}

void write_pooled(JsonWriter& w, std::size_t correct, std::size_t total, const Interval& wilson) {
    w.begin_object();
    w.key("correct").value(static_cast<std::uint64_t>(correct));
    w.key("total").value(static_cast<std::uint64_t>(total));
    w.key("wilson95").begin_array().value(wilson.low).value(wilson.high).end_array();
    w.end_object();
}

// tuned_same_folds and nested, when run. `scheme`: a grouped / blocked CV's
// own tuning, whose tuning folds follow it ("tuning_folds" says so); the
// random k-fold's keep their fields as they always were.
void write_tuning(JsonWriter& w, const std::optional<TunedCv>& tuned, const std::optional<NestedCv>& nested,
                  const CvScheme* scheme) {
    if (tuned) {
        w.key("tuned_same_folds").begin_object();
        w.key("note").value("Bayesian optimisation scored on the folds it tuned on: optimistic (the paper's protocol)");
        if (scheme) w.key("tuning_folds").value(scheme->describe());
        w.key("evaluations").value(static_cast<std::uint64_t>(tuned->search.history.size()));
        w.key("accuracy").value(tuned->same_folds_accuracy);
        w.key("parameters");
        write_params(w, tuned->search.best_params());
        w.end_object();
    }
    if (nested) {
        const auto& n = *nested;
        w.key("nested").begin_object();
        if (scheme)
            w.key("tuning_folds").value(scheme->describe() + ", built from each outer training fold's trials");
        w.key("mean").value(n.mean);
        w.key("sd").value(n.sd);
        w.key("per_outer_fold");
        write_numbers(w, n.outer_accuracy);
        w.key("pooled");
        write_pooled(w, n.correct, n.total, n.wilson);
        w.key("chosen").begin_array();
        for (const auto& p : n.chosen) write_params(w, p);
        w.end_array();
        w.end_object();
    }
}

void write_classifier(JsonWriter& w, const Evaluation& ev, const EvaluationReport& c) {
    const auto& b = c.baseline;
    w.begin_object();
    w.key("name").value(c.name);
    w.key("input").value(c.input);
    w.key("parameters");
    write_params(w, c.params);
    w.key("accuracy").begin_object();
    w.key("mean").value(b.mean);
    w.key("sd").value(b.sd);
    w.key("per_repeat");
    write_numbers(w, b.repeat_accuracy);
    // fold_accuracy is repetition-major; per repetition as many as its non-empty folds.
    w.key("per_fold").begin_array();
    const std::size_t per = b.repeats > 0 ? b.fold_accuracy.size() / static_cast<std::size_t>(b.repeats) : 0;
    for (int r = 0; r < b.repeats; ++r) {
        w.begin_array();
        for (std::size_t f = 0; f < per; ++f) w.value(b.fold_accuracy[static_cast<std::size_t>(r) * per + f]);
        w.end_array();
    }
    w.end_array();
    w.key("pooled");
    write_pooled(w, b.correct, b.total, b.wilson);
    w.end_object();
    w.key("cv_schemes").begin_array();
    for (const auto& s : c.scheme_cv) {
        w.begin_object();
        w.key("id").value(s.scheme.id());
        w.key("mean").value(s.cv.mean);
        w.key("sd").value(s.cv.sd);
        w.key("per_repeat");
        write_numbers(w, s.cv.repeat_accuracy);
        w.key("pooled");
        write_pooled(w, s.cv.correct, s.cv.total, s.cv.wilson);
        w.key("per_class_accuracy");
        write_numbers(w, s.cv.confusion.true_positive_rates());
        w.key("confusion");
        write_confusion(w, s.cv.confusion);
        write_tuning(w, s.tuned, s.nested, &s.scheme);
        w.end_object();
    }
    w.end_array();
    w.key("classes").begin_array();
    for (const auto& name : c.classes) w.value(name);
    w.end_array();
    w.key("per_class_accuracy");
    write_numbers(w, b.confusion.true_positive_rates());
    w.key("confusion");
    write_confusion(w, b.confusion);
    w.key("trials_used").begin_array();
    for (const auto& id : ev.trial_ids) w.value(id);
    w.end_array();
    w.key("trials_refused").begin_array();
    for (const auto& r : ev.refused)
        w.begin_object().key("trial").value(r.trial_id).key("reason").value(r.reason).end_object();
    w.end_array();
    if (const auto k = paper_refused_first_repeat(ev, c); k.total > 0) {
        w.key("paper_refused_trials").begin_object();
        w.key("total").value(static_cast<std::uint64_t>(k.total));
        w.key("correct_first_repeat").value(static_cast<std::uint64_t>(k.correct));
        w.key("accuracy_first_repeat").value(static_cast<double>(k.correct) / static_cast<double>(k.total));
        w.end_object();
    }
    w.key("first_repeat_predictions").begin_array();
    for (std::size_t i = 0; i < ev.trial_ids.size() && i < b.first_predicted.size(); ++i) {
        w.begin_object();
        w.key("trial").value(ev.trial_ids[i]);
        w.key("fold").value(ev.plan.assignment.empty() ? -1 : ev.plan.assignment.front()[i]);
        w.key("true").value(ev.classes[static_cast<std::size_t>(ev.truth[i])]);
        const int p = b.first_predicted[i];
        if (p >= 0) w.key("predicted").value(ev.classes[static_cast<std::size_t>(p)]);
        else w.key("predicted").null();
        w.key("scores");
        write_numbers(w, i < b.first_scores.size() ? b.first_scores[i] : std::vector<double>{});
        w.end_object();
    }
    w.end_array();
    write_tuning(w, c.tuned, c.nested, nullptr);
    w.key("seconds").value(c.seconds);
    w.end_object();
}

void write_point(JsonWriter& w, const PrefixPoint& p, bool with_seconds) {
    w.begin_object();
    w.key("fraction").value(p.fraction);
    if (with_seconds) w.key("seconds").value(p.seconds);
    w.key("accuracy").value(p.accuracy());
    w.key("correct").value(static_cast<std::uint64_t>(p.correct));
    w.key("no_decision").value(static_cast<std::uint64_t>(p.no_decision));
    w.key("total").value(static_cast<std::uint64_t>(p.total));
    w.end_object();
}

void write_prefixes(JsonWriter& w, const PrefixCurves& pc) {
    w.key("prefixes").begin_object();
    w.key("note").value(kPrefixTimingNote);
    w.key("fractions");
    write_numbers(w, pc.fractions);
    w.key("folds").value(pc.folds);
    w.key("repeats").value(pc.repeats);
    w.key("units").value(pc.units);
    w.key("nominal").begin_array();
    for (const auto& n : pc.nominal)
        w.begin_object()
            .key("speed").value(n.speed)
            .key("samples").value(n.samples)
            .key("seconds").value(n.seconds)
            .key("trials").value(static_cast<std::uint64_t>(n.trials))
            .end_object();
    w.end_array();
    w.key("classifiers").begin_array();
    for (const auto& c : pc.classifiers) {
        w.begin_object();
        w.key("name").value(c.classifier);
        w.key("input").value(c.input);
        w.key("points").begin_array();
        for (const auto& p : c.points) write_point(w, p, false);
        w.end_array();
        w.key("by_speed").begin_array();
        for (const auto& s : c.by_speed) {
            w.begin_object().key("speed").value(s.speed).key("points").begin_array();
            for (const auto& p : s.points) write_point(w, p, true);
            w.end_array().end_object();
        }
        w.end_array();
        w.key("fraction_95");
        if (c.fraction_95) w.value(*c.fraction_95);
        else w.null();
        w.end_object();
    }
    w.end_array();
    w.end_object();
}

}  // namespace

std::string evaluation_json(const Evaluation& ev) {
    JsonWriter w;
    w.begin_object();
    w.key("format").value("rollsense-evaluation");
    w.key("version").value(kEvaluationJsonVersion);
    w.key("input").value(ev.input);
    w.key("selection").value(ev.selection);
    if (!ev.series_time_axis.empty()) {
        w.key("series_time_axis").value(ev.series_time_axis);
        if (const auto caveat = time_axis_caveat(ev); !caveat.empty()) w.key("series_time_axis_note").value(caveat);
    }
    w.key("trials").value(static_cast<std::uint64_t>(ev.trials));
    w.key("clean").value(static_cast<std::uint64_t>(ev.clean));
    w.key("classes").begin_array();
    for (const auto& name : ev.classes) w.value(name);
    w.end_array();

    w.key("folds").begin_object();
    w.key("k").value(ev.plan.folds);
    w.key("repeats").value(static_cast<std::uint64_t>(ev.plan.repeats()));
    w.key("kind").value(ev.plan.grouped ? "grouped" : "stratified");
    w.key("seeds").begin_array();
    for (auto s : ev.plan.seeds) w.value(s);
    w.end_array();
    w.key("trials").begin_array();
    for (const auto& id : ev.trial_ids) w.value(id);
    w.end_array();
    write_assignment(w, ev.plan);
    w.end_object();

    w.key("cv_schemes").begin_array();
    for (const auto& s : ev.schemes) {
        w.begin_object();
        w.key("id").value(s.scheme.id());
        w.key("kind").value(s.scheme.kind == CvScheme::Kind::grouped ? "grouped" : "blocked");
        if (s.scheme.kind == CvScheme::Kind::grouped)
            w.key("group_by").value(s.scheme.group_by);
        else
            w.key("block").value(s.scheme.block);
        w.key("groups").value(static_cast<std::uint64_t>(s.groups));
        w.key("k").value(s.plan.folds);
        w.key("repeats").value(static_cast<std::uint64_t>(s.plan.repeats()));
        w.key("seeds").begin_array();
        for (auto seed : s.plan.seeds) w.value(seed);
        w.end_array();
        write_assignment(w, s.plan);
        w.end_object();
    }
    w.end_array();

    w.key("classifiers").begin_array();
    for (const auto& c : ev.classifiers) write_classifier(w, ev, c);
    w.end_array();

    w.key("paired_differences").begin_array();
    for (const auto& p : ev.paired) {
        const auto& d = p.difference;
        w.begin_object();
        w.key("a").value(ev.classifiers[p.a].name);
        w.key("b").value(ev.classifiers[p.b].name);
        w.key("n").value(static_cast<std::uint64_t>(d.n()));
        w.key("mean").value(d.mean);
        w.key("sd").value(d.sd);
        w.key("t").value(d.t);
        w.key("t_corrected").value(d.t_corrected);
        w.key("df").value(static_cast<std::int64_t>(d.n()) - 1);
        w.key("a_better").value(static_cast<std::uint64_t>(d.a_better));
        w.key("b_better").value(static_cast<std::uint64_t>(d.b_better));
        w.key("ties").value(static_cast<std::uint64_t>(d.ties));
        w.key("per_fold");
        write_numbers(w, d.per_fold);
        w.end_object();
    }
    w.end_array();
    if (ev.prefixes) write_prefixes(w, *ev.prefixes);
    w.key("seconds").value(ev.seconds);
    w.end_object();
    return w.str() + "\n";
}

}  // namespace rollsense::learn
