#include "analysis/learn/pipeline.hpp"

#include <algorithm>
#include <map>

#include "rollsense/atomic_file.hpp"
#include "analysis/learn/evaluation_json.hpp"
#include "analysis/learn/inputs.hpp"
#include "analysis/learn/plugin_factory.hpp"

namespace rollsense::learn {

std::string spec_name(const std::string& plugin, const ParamSet& own) {
    std::string name = plugin;
    for (const auto& [k, v] : own.values()) name += ":" + k + "=" + format_param_value(v);
    return name;
}

void make_names_unique(std::vector<ClassifierSpec>& specs) {
    std::map<std::string, int> seen;
    for (auto& s : specs)
        if (const int n = ++seen[s.name]; n > 1) s.name += " #" + std::to_string(n);
}

Result<std::vector<ClassifierSpec>> parse_classifier_list(const std::string& text, const ParamSet& common) {
    std::vector<ClassifierSpec> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find(',', start);
        if (end == std::string::npos) end = text.size();
        const std::string entry = text.substr(start, end - start);
        start = end + 1;
        if (entry.empty())
            return Error{ErrorCode::invalid_argument, "classifier list '" + text +
                                                          "' has an empty entry (write NAME[,NAME...], an entry "
                                                          "optionally NAME:KEY=VALUE)"};
        ClassifierSpec spec;
        ParamSet own;
        std::size_t colon = entry.find(':');
        spec.plugin = entry.substr(0, colon);
        if (spec.plugin.empty())
            return Error{ErrorCode::invalid_argument, "classifier entry '" + entry + "' has no plugin name before ':'"};
        while (colon != std::string::npos) {
            const std::size_t next = entry.find(':', colon + 1);
            const std::string assignment = entry.substr(colon + 1, next == std::string::npos ? next : next - colon - 1);
            if (auto st = parse_assignment(assignment, own); !st)
                return Error{st.code(), "classifier entry '" + entry + "': " + st.message()};
            colon = next;
        }
        spec.params = common;
        for (const auto& [k, v] : own.values()) spec.params.set(k, v);
        spec.name = spec_name(spec.plugin, own);
        out.push_back(std::move(spec));
        if (end == text.size()) break;
    }
    make_names_unique(out);
    return out;
}

std::vector<std::string> available_classifiers(runtime::PluginRegistry& registry) {
    std::vector<std::string> names;
    for (const auto& c : registry.scan())
        if (c.library && c.library->manifest().kind == PluginKind::classifier) names.push_back(c.library->name());
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

Result<std::vector<PreparedClassifier>> prepare_classifiers(runtime::PluginRegistry& registry,
                                                            const std::vector<ClassifierSpec>& specs) {
    if (specs.empty()) return Error{ErrorCode::invalid_argument, "no classifier requested"};
    // Every name first, so one typo in a list of several costs no extraction or training.
    for (const auto& s : specs) {
        if (registry.find(s.plugin, PluginKind::classifier)) continue;
        const auto names = available_classifiers(registry);
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        std::string where;
        for (const auto& d : registry.search_path()) where += (where.empty() ? "" : ", ") + d.string();
        return Error{ErrorCode::not_found,
                     "no classifier plugin named '" + s.plugin + "'. Available classifier plugins: " +
                         (list.empty() ? std::string("none") : list) + " (searched " + where +
                         "; add a folder with --plugin-path, `rollsense plugins` lists what loads)"};
    }
    std::vector<PreparedClassifier> out;
    for (const auto& s : specs) {
        auto factory = plugin_classifier_factory(registry, s.plugin);
        if (!factory) return factory.error();
        // One instance now: checks the parameters and tells the input kind.
        auto probe = (*factory)(s.params);
        if (!probe) return Status(probe.error()).with_context("classifier '" + s.name + "'");
        out.push_back({s, std::move(factory).value(), (*probe)->input()});
    }
    return out;
}

Result<InputTable> make_input_table(const std::vector<features::FeatureRow>& rows, ClassifierInput kind) {
    InputTable in;
    switch (kind) {
        case ClassifierInput::features:
            in.kind = "features";
            in.table = features::to_feature_table(rows, &in.row_of);
            return in;
        case ClassifierInput::series:
            // The one place the prepared-series step will be plugged in.
            return Error{ErrorCode::unsupported,
                         "classifiers that take the prepared series (input() = series) cannot be evaluated yet: "
                         "series preparation is not available in this version; use a feature-vector classifier"};
    }
    return Error{ErrorCode::invalid_argument, "unknown classifier input kind"};
}

Result<Evaluation> evaluate_prepared(const std::vector<features::FeatureRow>& rows,
                                     const std::vector<PreparedClassifier>& classifiers,
                                     const EvaluationOptions& options) {
    if (classifiers.empty()) return Error{ErrorCode::invalid_argument, "no classifier to evaluate"};
    const ClassifierInput kind = classifiers.front().input;
    for (const auto& c : classifiers)
        if (c.input != kind)
            return Error{ErrorCode::invalid_argument,
                         "classifiers '" + classifiers.front().spec.name + "' and '" + c.spec.name +
                             "' take different inputs (features and series); a paired comparison needs one input "
                             "table: evaluate them separately"};
    auto input = make_input_table(rows, kind);
    if (!input) return input.error();
    std::vector<ClassifierRequest> requests;
    for (const auto& c : classifiers) requests.push_back({c.spec.name, c.factory, c.spec.params});
    auto ev = evaluate_table(rows, input->table, input->row_of, requests, options);
    if (!ev) return ev.error();
    ev->input = input->kind;
    return ev;
}

Result<PipelineResult> run_pipeline(runtime::PluginRegistry& registry, const PipelineRequest& request,
                                    const std::function<Status(const std::vector<features::FeatureRow>&)>& on_rows,
                                    PipelineStage* failed) {
    auto fail = [failed](PipelineStage stage, Error e) -> Result<PipelineResult> {
        if (failed) *failed = stage;
        return e;
    };
    PipelineResult out;
    auto prepared = prepare_classifiers(registry, request.classifiers);
    if (!prepared) return fail(PipelineStage::classifiers, prepared.error());
    out.classifiers = std::move(prepared).value();
    auto rows = load_feature_rows(request.input, request.features);
    if (!rows) return fail(PipelineStage::rows, rows.error());
    out.rows = std::move(rows).value();
    if (on_rows)
        if (auto st = on_rows(out.rows); !st) return fail(PipelineStage::rows, st.error());
    auto ev = evaluate_prepared(out.rows, out.classifiers, request.options);
    if (!ev) return fail(PipelineStage::evaluation, ev.error());
    out.evaluation = std::move(ev).value();
    return out;
}

std::filesystem::path json_path_beside(const std::filesystem::path& text_path) {
    auto p = text_path;
    p.replace_extension(".json");
    if (p == text_path) p += ".json";  // a text file already named *.json: keep both
    return p;
}

Status write_evaluation_files(const Evaluation& evaluation, const std::filesystem::path& text_path) {
    if (auto st = write_file_atomic(text_path, format_evaluation(evaluation)); !st)
        return {st.code(), "cannot write '" + text_path.string() + "': " + st.message()};
    const auto json = json_path_beside(text_path);
    if (auto st = write_file_atomic(json, evaluation_json(evaluation)); !st)
        return {st.code(), "cannot write '" + json.string() + "': " + st.message()};
    return {};
}

}  // namespace rollsense::learn
