// Identification before the roll ends, from Lua: rs.prefix_models{...} trains
// one model per fraction of the roll on a recorded dataset's prefixes, for a
// script that stops rolling once it is sure (scripts/examples/identify_early.lua,
// docs/identification.md "Stopping early"). Live, such a model is used with
// clf:identify{open_end = true} on the recording so far.
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "rollsense/dataset.hpp"
#include "rollsense/log.hpp"
#include "analysis/lua/slice_guard.hpp"
#include "analysis/learn/pipeline.hpp"
#include "analysis/learn/prefix_evaluation.hpp"
#include "runtime/lua/api_internal.hpp"
#include "runtime/lua/lua_values.hpp"

namespace rollsense::runtime::lua_api {
namespace {

void check(lua_State* L, const Status& s) {
    if (!s.ok()) raise_status(L, s);
}

// A model's file is named by its fraction in whole percent: "-f030.rsm".
std::string model_file_suffix(double fraction) {
    char file[64];
    std::snprintf(file, sizeof file, "-f%03d.rsm", static_cast<int>(std::lround(100.0 * fraction)));
    return file;
}

std::vector<double> fractions_from(lua_State* L, int opts) {
    std::vector<double> out;
    lua_getfield(L, opts, "fractions");
    if (lua_isnil(L, -1)) {
        for (int k = 1; k <= 10; ++k) out.push_back(k / 10.0);  // 10 %, 20 %, ... 100 %, as the curves
    } else if (lua_istable(L, -1)) {
        for (lua_Integer i = 1; i <= static_cast<lua_Integer>(lua_rawlen(L, -1)); ++i) {
            lua_rawgeti(L, -1, i);
            if (!lua_isnumber(L, -1))
                luaL_error(L, "rs.prefix_models: fractions[%d] is not a number (a share of the roll in (0, 1])",
                           static_cast<int>(i));
            out.push_back(lua_tonumber(L, -1));
            lua_pop(L, 1);
        }
    } else {
        luaL_error(L, "rs.prefix_models: fractions must be a list of numbers in (0, 1], e.g. {0.3, 0.6, 1}");
    }
    lua_pop(L, 1);
    // User review: {0.12, 0.124} saved one model over the other, and returned both paths.
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (model_file_suffix(out[i]) == model_file_suffix(out[j])) {
                char message[256];  // luaL_error has no %g
                std::snprintf(message, sizeof message,
                              "rs.prefix_models: fractions[%zu] (%g) and fractions[%zu] (%g) would both be saved as "
                              "NAME%s (models are named by whole percent): give each fraction once, at least 0.01 apart",
                              j + 1, out[j], i + 1, out[i], model_file_suffix(out[i]).c_str());
                luaL_error(L, "%s", message);
            }
    return out;
}

// speeds = {10, "15", ...}: the speeds the models will be used at. Each must be among DIR's trials, checked before any
// training (user review: identify_early.lua found a speed the recording lacks only after training every model).
void check_speeds(lua_State* L, int opts, const std::string& dataset) {
    lua_getfield(L, opts, "speeds");
    if (lua_isnil(L, -1)) return lua_pop(L, 1);
    if (!lua_istable(L, -1)) luaL_error(L, "rs.prefix_models: speeds must be a list of speed labels, e.g. {10, 15, 20}");
    auto read = DatasetReader::open(dataset);
    check(L, read.status());
    std::set<std::string> recorded;
    for (const auto& t : read->trials()) recorded.insert(t.info.speed);
    for (lua_Integer i = 1; i <= static_cast<lua_Integer>(lua_rawlen(L, -1)); ++i) {
        lua_rawgeti(L, -1, i);
        if (lua_type(L, -1) != LUA_TSTRING && !lua_isinteger(L, -1))
            luaL_error(L, "rs.prefix_models: speeds[%d] is %s, not a speed label (a whole number or a string)",
                       static_cast<int>(i), shown_value(L, -1));
        const std::string speed = lua_tostring(L, -1);
        lua_pop(L, 1);
        if (recorded.count(speed)) continue;
        std::string known;
        for (const auto& r : recorded) known += (known.empty() ? "" : ", ") + r;
        luaL_error(L, "rs.prefix_models: speed %s is not among the trials of %s (its speeds: %s), so no prefix model "
                   "would have seen it: record that speed, or leave it out", speed.c_str(), dataset.c_str(),
                   known.c_str());
    }
    lua_pop(L, 1);
}

// rs.prefix_models{ dataset = DIR, classifier = "minirocket", fractions = {0.1, ..., 1}, name = "prefix", speeds = }
//   → { units = U,   (the nominal roll in clock units: what the fractions are fractions of)
//       nominal = { ["10"] = {samples=, seconds=}, ... },   (per speed, after the clock's zero, for reading)
//       models = { {fraction=, path=, trained=, refused=}, ... } }   (models saved as --out/NAME-f030.rsm;
//       no path where the prefixes the series rule accepts show fewer than two objects)
int l_prefix_models(lua_State* L) {
    Session& s = Session::of(L);
    luaL_checktype(L, 1, LUA_TTABLE);
    check_options(L, 1, "rs.prefix_models", {"dataset", "classifier", "fractions", "name", "series_amplitude", "speeds"});
    if (s.output_dir().empty()) return luaL_error(L, "rs.prefix_models saves models: run with --out DIR");
    const std::string dataset = opt_field_string(L, 1, "dataset", "");
    if (dataset.empty())
        return luaL_error(L, "rs.prefix_models: give dataset = '<folder of a recorded dataset>' to train on");
    const std::string name = opt_field_string(L, 1, "name", "prefix");
    check(L, Session::check_output_name(name + "-f100.rsm", "rs.prefix_models: name"));
    const std::vector<double> fractions = fractions_from(L, 1);
    check_speeds(L, 1, dataset);

    auto specs = learn::parse_classifier_list(opt_field_string(L, 1, "classifier", "minirocket"));
    check(L, specs.status());
    if (specs->size() != 1) return luaL_error(L, "rs.prefix_models: give one classifier, not a list");
    auto prepared = learn::prepare_classifiers(s.registry(), *specs);
    check(L, prepared.status());
    learn::InputOptions inputs;
    if (const auto a = opt_field_string(L, 1, "series_amplitude", ""); !a.empty()) {
        auto amp = learn::parse_amplitude(a);
        if (!amp) raise_status(L, Status(amp.error()).with_context("rs.prefix_models"));
        inputs.series.amplitude = *amp;
        inputs.amplitude_named = true;
    }
    auto trained = [&] {
        SliceGuard guard{s.sandbox(), L};
        return learn::train_prefix_models(dataset, prepared->front(), inputs, fractions);
    }();
    check(L, trained.status());

    lua_newtable(L);
    lua_pushnumber(L, trained->units);
    lua_setfield(L, -2, "units");
    lua_newtable(L);
    for (const auto& nl : trained->nominal) {
        lua_newtable(L);
        lua_pushnumber(L, nl.samples);
        lua_setfield(L, -2, "samples");
        lua_pushnumber(L, nl.seconds);
        lua_setfield(L, -2, "seconds");
        lua_setfield(L, -2, nl.speed.c_str());
    }
    lua_setfield(L, -2, "nominal");
    lua_createtable(L, static_cast<int>(trained->models.size()), 0);
    for (std::size_t i = 0; i < trained->models.size(); ++i) {
        const auto& m = trained->models[i];
        const std::string file = model_file_suffix(m.fraction);
        lua_newtable(L);
        lua_pushnumber(L, m.fraction);
        lua_setfield(L, -2, "fraction");
        if (m.model) {  // no model where the prefixes show fewer than two objects
            const auto path = s.output_dir() / (name + file);
            check(L, m.model->save(path));
            lua_pushstring(L, path.c_str());
            lua_setfield(L, -2, "path");
        }
        lua_pushinteger(L, static_cast<lua_Integer>(m.trained));
        lua_setfield(L, -2, "trained");
        lua_pushinteger(L, static_cast<lua_Integer>(m.refused));
        lua_setfield(L, -2, "refused");
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "models");
    log_info("analysis", std::to_string(trained->models.size()) + " prefix models of '" + specs->front().name +
                             "' saved as " + (s.output_dir() / (name + "-fNNN.rsm")).string());
    return 1;
}

void register_early(lua_State* L) {
    lua_pushcfunction(L, l_prefix_models);
    lua_setfield(L, -2, "prefix_models");
}

const ExtraRegistration registration{&register_early};

}  // namespace
}  // namespace rollsense::runtime::lua_api
