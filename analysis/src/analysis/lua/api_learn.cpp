// Identification from Lua: rs.analyse{...} turns the run's dataset into
// features, an evaluation and a trained model (the end of the stock
// experiment); rs.classifier{...} loads a model and :identify() names the
// object just rolled (live identification).
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "rollsense/features.hpp"
#include "rollsense/features/recorded.hpp"
#include "rollsense/log.hpp"
#include "analysis/learn/defaults.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/learn/evaluation_json.hpp"
#include "analysis/learn/inputs.hpp"
#include "analysis/learn/model_header.hpp"
#include "analysis/learn/pipeline.hpp"
#include "analysis/learn/plugin_factory.hpp"
#include "analysis/lua/prediction_observer.hpp"
#include "analysis/lua/slice_guard.hpp"
#include "analysis/lua/unfinished_analysis.hpp"
#include "runtime/lua/api_internal.hpp"
#include "runtime/lua/lua_values.hpp"
#include "analysis/report/report.hpp"
#include "analysis/series/model_rule.hpp"
#include "analysis/series/contact_clock.hpp"
#include "analysis/series/prepare.hpp"

namespace rollsense::runtime::lua_api {
namespace {

constexpr const char* kClassifierMeta = "rollsense.classifier";

void check(lua_State* L, const Status& s) {
    if (!s.ok()) raise_status(L, s);
}

ParamSet params_from(lua_State* L, int table) {
    ParamSet out;
    if (lua_isnoneornil(L, table)) return out;
    lua_getfield(L, table, "params");
    auto raw = lua_to_param_map(L, -1, "params");
    lua_pop(L, 1);
    if (!raw) raise_status(L, raw.status());
    for (auto& [k, v] : *raw) out.set(k, v);
    return out;
}

// Whether two spellings name one folder (through links, as the dataset is read).
bool same_folder(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code ec_a, ec_b;  // two paths that cannot be resolved are not one folder (diff review)
    const auto ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ec_a);
    const auto cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b), ec_b);
    return !ec_a && !ec_b && ca == cb;
}

// The last name of a folder however spelt ("runs/paper11/", "../paper11"), as an output name can hold it (letters,
// digits, '.', '_', '-'; any other character, a space say, becomes '_'): the tag of its analysis.
std::string folder_name(const std::filesystem::path& folder) {
    std::error_code ec;
    auto full = std::filesystem::weakly_canonical(std::filesystem::absolute(folder), ec);
    if (full.filename().empty()) full = full.parent_path();
    std::string name = full.filename().string();
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
    return name;
}

// The dataset each tag's outputs describe in this session ("" the untagged): two datasets under one tag, two folders of
// one name say, would write the same files, the second's replacing the first's (diff review).
std::map<std::string, std::filesystem::path>& tagged_datasets() {
    static std::map<std::string, std::filesystem::path> datasets;
    return datasets;
}

// The dataset of the rs.analyse under way (unfinished_analysis()): set when it starts, cleared when it returns.
std::optional<std::filesystem::path>& analysis_under_way() {
    static std::optional<std::filesystem::path> dataset;
    return dataset;
}


// The classifier list of rs.analyse: `classifiers = {"a", "b:learners=10"}`
// or the single `classifier = "a"`; entries as on the command line.
std::vector<learn::ClassifierSpec> classifier_specs_from(lua_State* L, int opts, const ParamSet& common) {
    std::string list;
    lua_getfield(L, opts, "classifiers");
    if (lua_istable(L, -1)) {
        const auto n = static_cast<lua_Integer>(lua_rawlen(L, -1));
        if (n == 0) luaL_error(L, "rs.analyse: classifiers = {} is empty; give at least one plugin name");
        for (lua_Integer i = 1; i <= n; ++i) {
            lua_rawgeti(L, -1, i);
            if (!lua_isstring(L, -1))
                luaL_error(L, "rs.analyse: classifiers[%d] is not a string (a classifier plugin name)",
                           static_cast<int>(i));
            list += (list.empty() ? "" : ",") + std::string(lua_tostring(L, -1));
            lua_pop(L, 1);
        }
    } else if (!lua_isnil(L, -1)) {
        luaL_error(L, "rs.analyse: classifiers must be a list of plugin names, e.g. {\"NAME\"}");
    }
    lua_pop(L, 1);
    if (list.empty()) {
        auto chosen = learn::classifier_or_default(opt_field_string(L, opts, "classifier", ""),
                                                   Session::of(L).options().share_dir);
        if (!chosen) raise_status(L, Status(chosen.error()).with_context("rs.analyse"));
        list = *chosen;
    }
    auto specs = learn::parse_classifier_list(list, common);
    if (!specs) raise_status(L, Status(specs.error()).with_context("rs.analyse"));
    return std::move(specs).value();
}

// rs.analyse{ folds=5, repeats=10, optimize=false, evaluations=30, classifier=<share/analysis/defaults.csv>,
//             classifiers={"a","b"}, params={...}, model="model.rsm",
//             trials="clean"|"all", series_amplitude="global_scale"|"z_per_channel",
//             series_time_axis="contact"|"roll_relative" (outside the paper's timing rule; no model is saved
//             for a series classifier with it),
//             dataset=DIR (default: this run's), tag="NAME" (outputs evaluation-NAME.*, report-NAME.html),
//             prefixes=false (identification before the roll ends), prefix_repeats=1,
//             cv="random"|"grouped,blocked", group_by=COLUMN, block=N (grouped/blocked CV beside
//             random k-fold: learn/cv_scheme.hpp) }
//             → summary table
// accuracy_sd of the table on top: nil with one repetition (no spread, learn::has_spread).
void set_sd(lua_State* L, double sd) {
    if (!learn::has_spread(sd)) return;
    lua_pushnumber(L, sd);
    lua_setfield(L, -2, "accuracy_sd");
}

int l_analyse(lua_State* L) {
    Session& s = Session::of(L);
    SliceGuard guard{s.sandbox(), L};
    const int opts = 1;
    check_options(L, opts, "rs.analyse", {"model", "dataset", "tag", "folds", "repeats", "params", "optimize",
                                          "nested", "evaluations", "classifier", "classifiers", "trials",
                                          "prefixes", "prefix_repeats", "series_amplitude", "series_time_axis",
                                          "cv", "group_by", "block"});
    // cv is one text, its schemes separated by commas: a table of them met the generic "option 'cv' must be a
    // string" (user review), which names neither rs.analyse nor the form it takes.
    if (lua_istable(L, opts)) {
        lua_getfield(L, opts, "cv");
        if (!lua_isnil(L, -1) && !lua_isstring(L, -1))
            return luaL_error(L, "rs.analyse: cv must be a string of comma-separated schemes (e.g. cv = "
                                 "\"grouped,blocked\"), got a %s", luaL_typename(L, -1));
        lua_pop(L, 1);
    }
    if (s.output_dir().empty()) return luaL_error(L, "rs.analyse needs a dataset: run with --out DIR");
    // dataset = DIR analyses a dataset recorded earlier (outputs still go to --out);
    // tag = "NAME" names the outputs evaluation-NAME.txt/.json, report-NAME.html and
    // model-NAME.rsm, so that one script can write several analyses side by side.
    std::string dataset = opt_field_string(L, opts, "dataset", "");
    if (!dataset.empty() && same_folder(dataset, s.output_dir())) dataset.clear();  // this run's own, however spelt
    const std::filesystem::path dataset_dir = dataset.empty() ? s.output_dir() : std::filesystem::path(dataset);
    if (const auto& shard = s.options().shard; shard && dataset.empty())
        return luaL_error(L, "rs.analyse: this run is shard %s and holds only its part of the trials; analyse the "
                             "merged dataset instead (rollsense merge, docs/cluster.md): skip the analysis when "
                             "rs.shard() returns n > 1", shard->text().c_str());
    analysis_under_way() = dataset_dir;  // from here on, a failure is the analysis's, not the recording's
    // Another dataset's results are tagged with its folder's name unless tag= names them: untagged, they would pass
    // for this run's own dataset's (review: OTHER's evaluation.txt and model.rsm beside this run's trials).
    const std::string tag = opt_field_string(L, opts, "tag", dataset.empty() ? "" : folder_name(dataset));
    if (tag.find('/') != std::string::npos || (!tag.empty() && tag[0] == '.'))
        return luaL_error(L, "rs.analyse: tag '%s' (given, or the folder name of dataset=) must be a plain name (no '/', "
                             "no leading '.'); give tag=\"NAME\"", tag.c_str());
    // Taken when its outputs are written (diff review: an analysis that failed before writing took the tag).
    if (const auto earlier = tagged_datasets().find(tag);
        earlier != tagged_datasets().end() && !same_folder(earlier->second, dataset_dir))
        return luaL_error(L, "rs.analyse: the outputs of %s would replace those of %s, analysed earlier in this run under "
                             "the same %s; give this analysis a tag of its own (tag=\"NAME\")",
                          dataset_dir.c_str(), earlier->second.c_str(),
                          tag.empty() ? "names (untagged)" : ("tag '" + tag + "'").c_str());
    const std::string suffix = tag.empty() ? "" : "-" + tag;
    // The model's name is checked before anything is written.
    const std::string model_name = opt_field_string(L, opts, "model", "model" + suffix + ".rsm");
    check(L, Session::check_output_name(model_name, "rs.analyse: model"));
    for (const char* own : {"evaluation.txt", "evaluation.json", "report.html"})
        if (model_name == own)
            return luaL_error(L, "rs.analyse: model '%s' cannot be written: rs.analyse writes %s itself; choose another "
                                 "name (e.g. model.rsm)", own, own);
    check(L, s.flush_dataset());

    learn::PipelineRequest request;
    request.input = dataset_dir;
    request.features = features::FeatureSettings{};
    // This run's own dataset: the features of the trials it recorded were taken
    // from memory as each became durable (register_learn); only resumed ones are read.
    auto* recorded = static_cast<const features::RecordedFeatures*>(lua_touserdata(L, lua_upvalueindex(1)));
    if (dataset.empty() && recorded && recorded->settings() == request.features) request.recorded = recorded;
    learn::EvaluationOptions& eo = request.options;
    eo.folds = static_cast<int>(opt_field_number(L, opts, "folds", 5));
    eo.repeats = static_cast<int>(opt_field_number(L, opts, "repeats", 10));
    // A dataset recorded earlier: the seed it was recorded with, as `rollsense evaluate DIR` takes it (user review:
    // the same dataset gave other figures here).
    eo.seed = dataset.empty() ? s.options().seed : learn::recorded_partition_seed(dataset_dir, s.options().seed);
    eo.params = params_from(L, opts);
    eo.optimize = opt_field_bool(L, opts, "optimize", false);
    eo.nested = opt_field_bool(L, opts, "nested", eo.optimize);
    eo.bayes.evaluations = static_cast<int>(opt_field_number(L, opts, "evaluations", eo.bayes.evaluations));
    {
        const double block = opt_field_number(L, opts, "block", 0);
        auto schemes = learn::parse_cv_schemes(opt_field_string(L, opts, "cv", ""),
                                               opt_field_string(L, opts, "group_by", ""),
                                               block == 0 ? "" : std::to_string(static_cast<long long>(block)));
        if (!schemes) raise_status(L, Status(schemes.error()).with_context("rs.analyse"));
        eo.schemes = std::move(schemes).value();
        // The model's tuning folds follow the scheme: refused now, not after the evaluation.
        if (auto st = learn::check_final_tuning(eo); !st) raise_status(L, std::move(st).with_context("rs.analyse"));
    }
    eo.progress = [](const std::string& line) { log_info("analysis", line); };
    eo.stop = &s.interrupt_flag();  // Ctrl-C stops the analysis, not only the roll
    request.classifiers = classifier_specs_from(L, opts, eo.params);
    // The input step: trials = "clean" (the paper's, default) | "all" (every trial the
    // series rule accepts; series classifiers only), series_amplitude = the series rule's mode.
    if (const auto t = opt_field_string(L, opts, "trials", ""); !t.empty()) {
        auto sel = learn::parse_trial_selection(t);
        if (!sel) raise_status(L, Status(sel.error()).with_context("rs.analyse"));
        request.inputs.trials = *sel;
    }
    if (opt_field_bool(L, opts, "prefixes", false)) {  // accuracy before the roll ends
        learn::PrefixOptions po;
        po.repeats = static_cast<int>(opt_field_number(L, opts, "prefix_repeats", 1));
        request.prefixes = po;
    }
    if (const auto a = opt_field_string(L, opts, "series_amplitude", ""); !a.empty()) {
        auto amp = learn::parse_amplitude(a);
        if (!amp) raise_status(L, Status(amp.error()).with_context("rs.analyse"));
        request.inputs.series.amplitude = *amp;
        request.inputs.amplitude_named = true;
    }
    if (const auto t = opt_field_string(L, opts, "series_time_axis", ""); !t.empty()) {
        auto axis = learn::parse_time_axis(t);
        if (!axis) raise_status(L, Status(axis.error()).with_context("rs.analyse"));
        request.inputs.series.time_axis = *axis;
        request.inputs.time_axis_named = true;
    }

    auto result = learn::run_pipeline(s.registry(), request, [&s, &dataset](const std::vector<features::FeatureRow>& rows) {
        // The features belong beside the dataset they were made from; a dataset
        // recorded earlier is left as it is.
        if (dataset.empty())
            if (auto st = features::write_features_csv(s.output_dir() / "features.csv", rows); !st) return st;
        return Status{};  // the clean count and rejections: in the summary that follows
    });
    check(L, result.status());
    const learn::Evaluation& evaluation = result->evaluation;
    const learn::EvaluationReport& primary = evaluation.primary();
    tagged_datasets().emplace(tag, dataset_dir);
    check(L, s.write_output_text("evaluation" + suffix + ".txt", learn::format_evaluation(evaluation)));
    check(L, s.write_output_text("evaluation" + suffix + ".json", learn::evaluation_json(evaluation)));

    // report.html: the paper's figures and tables for this dataset, and the terminal summary.
    report::ReportInputs ri;
    ri.dataset_dir = dataset_dir;
    ri.output = s.output_dir() / ("report" + suffix + ".html");
    ri.rows = result->rows;
    ri.evaluation = evaluation;
    ri.command_line = s.options().command_line;
    if (dataset.empty())  // this run's own dataset: its run-info.csv comes when the run ends
        ri.recording_run = {{"command_line", s.options().command_line},
                            {"profile", s.profile().path.string()},
                            {"script", s.options().script.string()},
                            {"seed", std::to_string(s.options().seed)},
                            {"status", "running (this report is made by the script's rs.analyse)"}};
    auto page = report::write_report(ri);
    check(L, page.status());
    std::fprintf(stderr, "\n%s", report::text_summary(ri).c_str());
    log_info("analysis", "report written to " + page->string() +
                             "; the full evaluation is in evaluation" + suffix + ".txt and evaluation" + suffix +
                             ".json");

    // The model to deploy is the first classifier's.
    const auto& first = result->classifiers.front();
    eo.params = first.spec.params;
    const auto& rows = result->rows;
    // A series model prepared with a time axis outside the paper's timing rule
    // is for comparison only (its timing names a cylinder's diameter without
    // sensing its shape): it is evaluated, never deployed.
    const bool deployable = !(first.input == ClassifierInput::series &&
                              request.inputs.series.time_axis != series::TimeAxis::contact);
    std::filesystem::path model_path;
    if (deployable) {
        auto final_model = learn::fit_final_prepared(rows, dataset_dir, first, eo, request.inputs);
        check(L, final_model.status());
        model_path = s.output_dir() / model_name;
        check(L, final_model->classifier->save(model_path));
        log_info("analysis", "model saved to " + model_path.string() +
                                 (dataset.empty() ? "" : " (trained on " + dataset + ": predict with --training " + dataset + ")"));
    } else {
        log_warning("analysis", "no model saved: '" + first.spec.name + "' was evaluated with series_time_axis = " +
                                 std::string(series::to_string(request.inputs.series.time_axis)) + ", " +
                                 learn::kOutsideTimingRule + " (for comparison only)");
    }

    lua_newtable(L);
    const auto* report = &primary;
    lua_pushinteger(L, static_cast<lua_Integer>(report->trials));
    lua_setfield(L, -2, "trials");
    lua_pushinteger(L, static_cast<lua_Integer>(report->clean));
    lua_setfield(L, -2, "clean");
    lua_pushnumber(L, report->baseline.mean);
    lua_setfield(L, -2, "accuracy");
    set_sd(L, report->baseline.sd);
    lua_pushnumber(L, report->baseline.wilson.low);
    lua_setfield(L, -2, "interval_low");
    lua_pushnumber(L, report->baseline.wilson.high);
    lua_setfield(L, -2, "interval_high");
    if (report->nested) {
        lua_pushnumber(L, report->nested->mean);
        lua_setfield(L, -2, "nested_accuracy");
    }
    // Grouped / blocked CV of the first classifier: {id="grouped:speed", accuracy=, accuracy_sd=}.
    lua_createtable(L, static_cast<int>(report->scheme_cv.size()), 0);
    for (std::size_t i = 0; i < report->scheme_cv.size(); ++i) {
        const auto& sc = report->scheme_cv[i];
        lua_newtable(L);
        lua_pushstring(L, sc.scheme.id().c_str());
        lua_setfield(L, -2, "id");
        lua_pushnumber(L, sc.cv.mean);
        lua_setfield(L, -2, "accuracy");
        set_sd(L, sc.cv.sd);
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "cv");
    // Every classifier compared, in the order given: {name=, accuracy=, accuracy_sd=}.
    lua_createtable(L, static_cast<int>(evaluation.classifiers.size()), 0);
    for (std::size_t i = 0; i < evaluation.classifiers.size(); ++i) {
        const auto& c = evaluation.classifiers[i];
        lua_newtable(L);
        lua_pushstring(L, c.name.c_str());
        lua_setfield(L, -2, "name");
        lua_pushnumber(L, c.baseline.mean);
        lua_setfield(L, -2, "accuracy");
        set_sd(L, c.baseline.sd);
        // With trials = "all": how it did on the trials the paper's peak rule refuses.
        if (const auto k = learn::paper_refused_first_repeat(evaluation, c); k.total > 0) {
            lua_pushinteger(L, static_cast<lua_Integer>(k.total));
            lua_setfield(L, -2, "paper_refused");
            lua_pushinteger(L, static_cast<lua_Integer>(k.correct));
            lua_setfield(L, -2, "paper_refused_correct");
        }
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "classifiers");
    if (!model_path.empty()) {  // nil when no model was saved (series_time_axis = "roll_relative")
        lua_pushstring(L, model_path.c_str());
        lua_setfield(L, -2, "model");
    }
    lua_pushstring(L, (s.output_dir() / ("evaluation" + suffix + ".json")).c_str());
    lua_setfield(L, -2, "evaluation");
    if (dataset.empty()) {  // written only beside this run's own dataset
        lua_pushstring(L, (s.output_dir() / "features.csv").c_str());
        lua_setfield(L, -2, "features");
    }
    lua_pushstring(L, page->c_str());
    lua_setfield(L, -2, "report");
    analysis_under_way().reset();
    return 1;
}

// A live classifier, or an error: a method never runs on a freed object.
learn::ClassifierPtr& check_classifier(lua_State* L, int index) {
    auto& p = *static_cast<learn::ClassifierPtr*>(luaL_checkudata(L, index, kClassifierMeta));
    if (!p) luaL_error(L, "this classifier has been released; load it again with rs.classifier{...}");
    return p;
}

// Lua's finalizer (scripts cannot reach it: the metatable is protected).
// Emptied rather than destroyed: an empty pointer owns nothing, so a second
// call frees nothing twice and a method call after it sees "released".
int l_classifier_gc(lua_State* L) {
    static_cast<learn::ClassifierPtr*>(luaL_checkudata(L, 1, kClassifierMeta))->reset();
    return 0;
}

// rs.classifier{ model = PATH, classifier = <the plugin the model file names> } → a loaded model
int l_classifier(lua_State* L) {
    Session& s = Session::of(L);
    SliceGuard guard{s.sandbox(), L};
    luaL_checktype(L, 1, LUA_TTABLE);
    check_options(L, 1, "rs.classifier", {"model", "classifier"});
    const std::string model = opt_field_string(L, 1, "model", "");
    if (model.empty()) return luaL_error(L, "rs.classifier: give model = '<path of a saved model>'");
    check(L, learn::check_model_file(model));  // before any plugin reads it
    // As `rollsense predict`: the plugin the model's first line names (plugin review: a plugin's model was read as a
    // bagged-trees one, the stock default, and refused). A file that names none is left to the default plugin's
    // load, which says what is wrong with it, as before.
    const std::string given = opt_field_string(L, 1, "classifier", "");
    std::string named;  // the plugin the file names, when no classifier is given
    if (given.empty())
        if (auto header = learn::read_model_header(model))
            if (auto plugin = learn::plugin_named_by(*header, model)) named = *plugin;
    auto chosen = learn::classifier_or_default(given.empty() ? named : given, s.options().share_dir);
    check(L, chosen.status());
    auto factory = learn::plugin_classifier_factory(s.registry(), *chosen);
    if (!factory && !named.empty()) {
        Error e = factory.error();
        e.message += learn::named_by_note(model, "give classifier = NAME");
        raise_status(L, Status(e));
    }
    check(L, factory.status());
    auto clf = (*factory)(ParamSet{});
    check(L, clf.status());
    check(L, (*clf)->load(model));
    // A series model's recorded rule is read now, so a malformed one is named with its file here.
    if ((*clf)->input() == ClassifierInput::series) check(L, series::model_rule(**clf, model).status());
    new (lua_newuserdatauv(L, sizeof(learn::ClassifierPtr), 0)) learn::ClassifierPtr(std::move(*clf));
    luaL_setmetatable(L, kClassifierMeta);
    return 1;
}

PredictionObserver& prediction_observer() {
    static PredictionObserver observer;
    return observer;
}

void push_prediction(lua_State* L, const Classifier& clf, const Prediction& p) {
    if (const auto& observer = prediction_observer()) observer(L, clf.class_names(), p);
    lua_newtable(L);
    lua_pushstring(L, p.class_name.c_str());
    lua_setfield(L, -2, "object");
    lua_newtable(L);
    const auto names = clf.class_names();
    for (std::size_t i = 0; i < names.size() && i < p.scores.size(); ++i) {
        lua_pushnumber(L, p.scores[i]);
        lua_setfield(L, -2, names[i].c_str());
    }
    lua_setfield(L, -2, "scores");
}

// A series model (minirocket) identifies from the recording prepared by the
// one series rule, with the settings it was trained with, which its model
// file records (series/model_rule.hpp). A file written before it recorded
// them is prepared by the documented defaults, or by
// clf:identify{series_amplitude = "z_per_channel"} for a model trained so; a
// series_amplitude that contradicts the recorded rule is refused.
// clf:identify{open_end = true} during the roll (before rs.record_stop) treats
// the recording so far as a prefix: a contact it cuts off is not refused.
int identify_series(lua_State* L, const Classifier& clf, const TrialData& data,
                    const std::array<std::size_t, features::kChannels>& columns) {
    auto rule = series::model_rule(clf, "the model of rs.classifier");  // read once already when it was loaded
    check(L, Status(rule.status()).with_context("identify"));
    series::SeriesSettings settings = rule->settings;
    if (lua_istable(L, 2)) {
        settings.open_end = opt_field_bool(L, 2, "open_end", false);
        const std::string amplitude = opt_field_string(L, 2, "series_amplitude", "");
        if (!amplitude.empty()) {
            auto a = learn::parse_amplitude(amplitude);
            if (!a) raise_status(L, Status(a.error()).with_context("identify"));
            if (rule->recorded && *a != settings.amplitude)
                raise_status(L, {ErrorCode::invalid_argument,
                                 "identify: series_amplitude = '" + amplitude + "', but the model was trained with '" +
                                     std::string(series::to_string(settings.amplitude)) +
                                     "' (its file records the series rule): leave series_amplitude out"});
            settings.amplitude = *a;
        }
    }
    auto prepared = series::prepare_series(data, columns, settings);
    check(L, prepared.status());
    if (!prepared->ok) {
        lua_pushnil(L);
        lua_pushstring(L, ("series rule: " + prepared->reason).c_str());
        return 2;
    }
    auto p = clf.predict(prepared->values);
    check(L, p.status());
    push_prediction(L, clf, *p);
    return 1;
}

// The channels the identification reads in this run's recording: the profile's
// identification_channels among the robot's channel columns (as a dataset of it names them).
Result<std::array<std::size_t, features::kChannels>> recording_channels(Session& s) {
    DatasetInfo live;
    live.channels = s.robot().channel_columns();
    live.identification_channels = s.profile().identification_channels;
    return features::identification_channels(live, std::string());  // the caller names the profile
}

// rs.identification_channels() → the three channel columns the identification
// reads, in crossing order. A script that analyses at its end calls it before
// its first trial, so a profile the analysis cannot read stops the run there.
int l_identification_channels(lua_State* L) {
    Session& s = Session::of(L);
    auto columns = recording_channels(s);
    if (!columns)  // the profile's mistake, reported as its others are (exit 3)
        raise_status(L, {ErrorCode::parse_error, s.profile().path.string() + ": " + columns.error().message});
    lua_createtable(L, static_cast<int>(features::kChannels), 0);
    for (std::size_t c = 0; c < features::kChannels; ++c) {
        lua_pushstring(L, s.robot().channel_columns()[(*columns)[c]].c_str());
        lua_rawseti(L, -2, static_cast<lua_Integer>(c + 1));
    }
    return 1;
}

// clf:identify() → prediction table, or nil and the rejection reason when the
// recording has no clean peaks (e.g. the object did not cross all three sensors)
// or, for a series model, when the series rule refuses it.
int l_identify(lua_State* L) {
    auto& clf = check_classifier(L, 1);
    // Checked for every model (review: a mistyped option was silently ignored by a feature model); the two concern
    // the series rule, so a feature model, whose peaks need the whole contact, reads neither.
    check_options(L, 2, "identify", {"series_amplitude", "open_end"});
    (void)opt_field_bool(L, 2, "open_end", false);  // its type, for every model
    Session& s = Session::of(L);
    const auto& data = s.recorded();
    if (data.samples() == 0) return luaL_error(L, "identify: nothing recorded (rs.record_start/stop first)");
    auto columns = recording_channels(s);
    check(L, Status(columns.status()).with_context("identify"));
    if (clf->input() == ClassifierInput::series) return identify_series(L, *clf, data, *columns);
    const features::IdentificationInput in = features::identification_input(data, *columns);
    features::FeatureExtractor extractor;
    auto f = extractor.extract(std::span<const std::span<const double>>(in.channels), in.time);
    check(L, f.status());
    if (!f->clean) {
        lua_pushnil(L);
        lua_pushstring(L, f->reason.c_str());
        return 2;
    }
    auto p = clf->predict(f->values);
    check(L, p.status());
    push_prediction(L, *clf, *p);
    lua_newtable(L);
    for (std::size_t i = 0; i < features::kFeatureCount; ++i) {
        lua_pushnumber(L, f->values[i]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "features");
    return 1;
}

// clf:contact_progress(units) → the share of a nominal roll of `units` clock
// units that the recording so far has reached on the contact's own clock
// (series::contact_clock, read with the series rule the model records), or
// nil before the clock is known. The same figure rs.prefix_models cut the
// prefixes its models were trained on with (pass its `units`).
int l_contact_progress(lua_State* L) {
    auto& clf = check_classifier(L, 1);
    const double units = luaL_checknumber(L, 2);
    if (!(units > 0.0)) return luaL_error(L, "contact_progress: units must be > 0 (rs.prefix_models returns them)");
    if (clf->input() != ClassifierInput::series)
        return luaL_error(L, "contact_progress: the model takes features; the clock is read with a series model's "
                             "rule (e.g. a minirocket model)");
    Session& s = Session::of(L);
    auto columns = recording_channels(s);
    check(L, Status(columns.status()).with_context("contact_progress"));
    auto rule = series::model_rule(*clf, "the model of rs.classifier");
    check(L, Status(rule.status()).with_context("contact_progress"));
    const auto clock = series::contact_clock(s.recorded(), *columns, rule->settings);
    if (clock) lua_pushnumber(L, series::clock_progress(*clock, units, s.recorded().samples()));
    else lua_pushnil(L);
    return 1;
}

// clf:predict({f1, ..., f13}) → prediction table
int l_predict(lua_State* L) {
    auto& clf = check_classifier(L, 1);
    luaL_checktype(L, 2, LUA_TTABLE);
    std::vector<double> x;
    for (lua_Integer i = 1; i <= static_cast<lua_Integer>(lua_rawlen(L, 2)); ++i) {
        lua_rawgeti(L, 2, i);
        x.push_back(luaL_checknumber(L, -1));
        lua_pop(L, 1);
    }
    auto p = clf->predict(x);
    check(L, p.status());
    push_prediction(L, *clf, *p);
    return 1;
}

int l_classes(lua_State* L) {
    auto names = check_classifier(L, 1)->class_names();
    lua_createtable(L, static_cast<int>(names.size()), 0);
    for (std::size_t i = 0; i < names.size(); ++i) {
        lua_pushstring(L, names[i].c_str());
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    return 1;
}

void register_learn(lua_State* L) {
    static const luaL_Reg methods[] = {{"identify", l_identify}, {"predict", l_predict}, {"classes", l_classes},
                                       {"contact_progress", l_contact_progress},
                                       {nullptr, nullptr}};
    luaL_newmetatable(L, kClassifierMeta);
    protect_metatable(L);
    lua_newtable(L);
    luaL_setfuncs(L, methods, 0);
    lua_setfield(L, -2, "__index");
    lua_pushcfunction(L, l_classifier_gc);
    lua_setfield(L, -2, "__gc");
    lua_pop(L, 1);
    static const luaL_Reg fns[] = {
        {"classifier", l_classifier}, {"identification_channels", l_identification_channels}, {nullptr, nullptr}};
    luaL_setfuncs(L, fns, 0);
    analysis_under_way().reset();  // a new session
    tagged_datasets().clear();
    // Features from memory: every trial this session's recorder makes durable
    // goes through a RecordedFeatures, which rs.analyse reads (its upvalue). The
    // recorder's observer owns it, and the recorder outlives the Lua state.
    auto recorded = std::make_shared<features::RecordedFeatures>();
    lua_pushlightuserdata(L, recorded.get());
    lua_pushcclosure(L, l_analyse, 1);
    lua_setfield(L, -2, "analyse");
    Session::of(L).recorder().on_durable(
        [recorded](const DatasetInfo& info, const TrialRecord& record, const TrialData& data) {
            recorded->add(info, record, data);
        });
}

const ExtraRegistration registration{&register_learn};

}  // namespace

void set_prediction_observer(PredictionObserver observer) { prediction_observer() = std::move(observer); }
std::optional<std::filesystem::path> unfinished_analysis() { return analysis_under_way(); }

}  // namespace rollsense::runtime::lua_api
