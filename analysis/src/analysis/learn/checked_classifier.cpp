#include "analysis/learn/checked_classifier.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "rollsense/csv.hpp"

namespace rollsense::learn {

namespace {

// How far a plugin's scores may be from a distribution through rounding: a
// plugin computing in single precision still passes; a score of 7, or scores
// summing to 0.9, do not.
constexpr double kScoreTolerance = 1e-6;

using csv::format_number;

}  // namespace

Status check_prediction(const Prediction& p, const std::vector<std::string>& class_names, const std::string& who) {
    const std::size_t classes = class_names.size();
    const std::string n = std::to_string(classes);
    if (p.label < 0 || static_cast<std::size_t>(p.label) >= classes)
        return {ErrorCode::plugin_error,
                who + " predicted label " + std::to_string(p.label) + " outside its " + n + " classes"};
    const auto label = static_cast<std::size_t>(p.label);
    if (p.class_name != class_names[label])
        return {ErrorCode::plugin_error, who + " named its label " + std::to_string(p.label) + " '" + p.class_name +
                                             "', which is class '" + class_names[label] + "'"};
    if (p.scores.size() != classes)
        return {ErrorCode::plugin_error, who + " returned " + std::to_string(p.scores.size()) + " scores for " + n +
                                             " classes; a prediction has one score per class, in class order"};
    double sum = 0.0;
    for (std::size_t c = 0; c < classes; ++c) {
        if (!std::isfinite(p.scores[c]))
            return {ErrorCode::plugin_error, who + " returned a score that is not a finite number (" +
                                                 std::to_string(p.scores[c]) + ") for class '" + class_names[c] +
                                                 "' (" + std::to_string(c + 1) + " of " + n + ")"};
        if (p.scores[c] < 0.0)
            return {ErrorCode::plugin_error, who + " returned a negative score (" + format_number(p.scores[c]) +
                                                 ") for class '" + class_names[c] +
                                                 "'; scores are a distribution over the classes"};
        sum += p.scores[c];
    }
    if (std::abs(sum - 1.0) > kScoreTolerance)
        return {ErrorCode::plugin_error, who + " returned scores summing to " + format_number(sum) +
                                             "; scores are a distribution over the classes, summing to 1"};
    const auto top = static_cast<std::size_t>(std::max_element(p.scores.begin(), p.scores.end()) - p.scores.begin());
    if (p.scores[label] < p.scores[top] - kScoreTolerance)
        return {ErrorCode::plugin_error, who + " predicted '" + class_names[label] + "' (score " +
                                             format_number(p.scores[label]) + ") but scored '" + class_names[top] +
                                             "' highest (" + format_number(p.scores[top]) +
                                             "); the predicted class is the one with the highest score"};
    return {};
}

Status check_search_space(const SearchSpace& space, const ParamSchema& schema, const std::string& who) {
    for (const auto& d : space) {
        if (std::ranges::any_of(schema, [&](const ParamSpec& p) { return p.name == d.name; })) continue;
        std::string declared;
        for (const auto& p : schema) declared += (declared.empty() ? "" : ", ") + p.name;
        return {ErrorCode::plugin_error,
                who + " names the parameter '" + d.name + "' in its search_space(), which its schema() does not " +
                    "declare (it declares: " + (declared.empty() ? std::string("none") : declared) +
                    "), so tuning could not set it; the plugin must declare '" + d.name +
                    "' in schema() or drop it from search_space() (ask its author)"};
    }
    // A space the optimiser can search, of values the schema accepts (user review: k searched up to 50 against a
    // schema's [1, 10] failed at the first optimiser evaluation, after the preset's CV, read as the user's own k;
    // diff review: an empty range, a log scale from 0, a real scale for an integer, after the preset's CV too).
    using Scale = SearchDimension::Scale;
    for (const auto& d : space) {
        const bool real = d.scale == Scale::real_linear || d.scale == Scale::real_log;
        const auto spec = std::ranges::find(schema, d.name, &ParamSpec::name);  // declared: checked above
        const std::string wrong =
            d.scale == Scale::categorical ? (d.choices.empty() ? "no choices" : "")
            : !std::isfinite(d.low) || !std::isfinite(d.high)
                ? "a range that is not finite [" + format_number(d.low) + ", " + format_number(d.high) + "]"
            : !(d.high >= d.low)          ? "an empty range [" + format_number(d.low) + ", " + format_number(d.high) + "]"
            : (d.scale == Scale::integer_log || d.scale == Scale::real_log) && !(d.low > 0)
                ? "a log scale from " + format_number(d.low) + " (it must start above 0)"
            : real && spec->type == ParamType::integer ? "a real scale for an integer parameter"
                                                       : "";
        if (!wrong.empty())
            return {ErrorCode::plugin_error, who + ": search_space() gives '" + d.name + "' " + wrong +
                                                 ", which tuning cannot search: the plugin must fix its search_space() "
                                                 "(ask its author)"};
        std::vector<ParamValue> ends(d.choices.begin(), d.choices.end());
        if (d.scale == Scale::integer_linear || d.scale == Scale::integer_log)
            ends = {static_cast<std::int64_t>(d.low), static_cast<std::int64_t>(d.high)};
        else if (d.scale != Scale::categorical)
            ends = {d.low, d.high};
        for (const auto& value : ends)
            if (auto ok = validate_params(schema, {{d.name, value}}, who + ": search_space()"); !ok)
                return {ErrorCode::plugin_error, ok.error().message + "; tuning may try only values its schema() "
                                                 "accepts: the plugin must narrow its search_space() or widen its "
                                                 "schema() (ask its author)"};
    }
    return {};
}

Status in_classifier(Status status, const std::string& name) {
    if (status.message().starts_with("classifier plugin '" + name + "'")) return status;
    return std::move(status).with_context("classifier '" + name + "'");
}

namespace {

class CheckedClassifier final : public Classifier {
public:
    CheckedClassifier(ClassifierPtr inner, std::string who, ParamSchema schema)
        : inner_(std::move(inner)), who_(std::move(who)), schema_(std::move(schema)) {}

    ClassifierInput input() const override { return thrown("input", [&] { return inner_->input(); }); }
    SearchSpace search_space(std::size_t rows, std::size_t cols) const override {
        auto space = thrown("search_space", [&] { return inner_->search_space(rows, cols); });
        if (auto s = check_search_space(space, schema_, who_); !s) throw StatusError(s);
        return space;
    }
    Status train(const FeatureTable& data) override {
        // Its refusal named, as a throw is (review: train printed "refusing to train" alone).
        return counted("training", guarded("training", [&] { return Status(inner_->train(data)).with_context(who_); }));
    }
    // A model file is read only here: its errors name the plugin that read it.
    Status load(const std::filesystem::path& file) override {
        const std::string loading = "loading " + file.string();
        return counted(loading, guarded(loading, [&] { return Status(inner_->load(file)).with_context(who_); }));
    }
    Result<Prediction> predict(std::span<const double> features) const override {
        auto p = guarded("prediction", [&] { return inner_->predict(features); });
        if (!p) return p;
        if (auto s = check_prediction(*p, classes_, who_); !s) return s;
        return p;
    }
    std::vector<std::string> class_names() const override {
        return thrown("class_names", [&] { return inner_->class_names(); });
    }
    std::string series_rule() const override { return thrown("series_rule", [&] { return inner_->series_rule(); }); }
    Status save(const std::filesystem::path& file) const override {
        return guarded("saving " + file.string(), [&] { return inner_->save(file); });
    }
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override {
        return guarded("'" + verb + "'", [&] { return inner_->invoke(verb, args); });
    }

private:
    // The one place a call into the plugin is made: an exception it throws
    // (written outside this repository, it may) becomes a plugin error naming
    // it, with the exception's text, instead of ending the command as an
    // "unexpected error" or a thread with std::terminate.
    template <class Call>
    auto guarded(const std::string& during, Call&& call) const -> decltype(call()) {
        try {
            return call();
        } catch (const StatusError& e) {
            return Status(e.status()).with_context(who_ + " during " + during).error();
        } catch (const std::exception& e) {
            return Error{ErrorCode::plugin_error, who_ + " threw during " + during + ": " + e.what()};
        } catch (...) {
            return Error{ErrorCode::plugin_error, who_ + " threw during " + during + " (not a std::exception)"};
        }
    }

    // The calls with no error return: what the plugin throws is thrown on as
    // a StatusError (a plugin error naming it), which the command reports.
    template <class Call>
    auto thrown(const char* during, Call&& call) const -> decltype(call()) {
        auto r = guarded(during, [&] { return Result<decltype(call())>(call()); });
        if (!r) throw StatusError(r.status());
        return std::move(*r);
    }

    // The classes predictions are checked against, once the model exists
    // (train runs on the folds' threads: what class_names throws is returned).
    Status counted(const std::string& after, Status s) {
        if (!s) return s;
        auto names = guarded("class_names", [&] { return Result<std::vector<std::string>>(inner_->class_names()); });
        if (!names) return names.status();
        // Said as it is: with no classes every prediction was refused as "label 0 outside its 0 classes" (review).
        if (names->empty())
            return Error{ErrorCode::plugin_error,
                         who_ + " returned no class names after " + after +
                             " (class_names() is empty); a trained classifier names the classes it predicts, in "
                             "label order: fix the plugin or ask its author"};
        classes_ = std::move(*names);
        return {};
    }

    ClassifierPtr inner_;
    std::string who_;
    ParamSchema schema_;
    std::vector<std::string> classes_;
};

}  // namespace

ClassifierPtr checked_classifier(ClassifierPtr inner, std::string who, ParamSchema schema) {
    return std::make_shared<CheckedClassifier>(std::move(inner), std::move(who), std::move(schema));
}

}  // namespace rollsense::learn
