#include "analysis/series/model_rule.hpp"

#include <cmath>
#include <functional>
#include <set>
#include <type_traits>
#include <vector>

#include "rollsense/model_text.hpp"

namespace rollsense::series {
namespace {

using model_text::put_number;

// One setting: how it is written and read back.
struct Key {
    std::string_view name;
    std::function<void(const SeriesSettings&, std::string&)> put;
    std::function<bool(std::string_view, SeriesSettings&)> get;  // false: malformed value
};

template <class T>
bool number(std::string_view v, T& out) {
    T x{};
    if (!model_text::take(v, x) || !v.empty()) return false;  // take() leaves nothing of a lone number
    if constexpr (std::is_floating_point_v<T>)
        if (!std::isfinite(x)) return false;
    out = x;
    return true;
}

template <class T>
Key numeric(std::string_view name, T SeriesSettings::*field) {
    return {name, [field](const SeriesSettings& s, std::string& out) { put_number(out, s.*field); },
            [field](std::string_view v, SeriesSettings& s) { return number(v, s.*field); }};
}

template <class E>
Key word(std::string_view name, E SeriesSettings::*field, std::vector<E> choices) {
    return {name, [field](const SeriesSettings& s, std::string& out) { out += to_string(s.*field); },
            [field, choices](std::string_view v, SeriesSettings& s) {
                for (E c : choices)
                    if (v == to_string(c)) {
                        s.*field = c;
                        return true;
                    }
                return false;
            }};
}

// The settings in the order they are written; prefix and open_end are not
// among them (model_rule.hpp).
const std::vector<Key>& keys() {
    static const std::vector<Key> k{
        numeric("length", &SeriesSettings::length),
        numeric("detect_window", &SeriesSettings::detect_window),
        numeric("contact_fraction", &SeriesSettings::contact_fraction),
        numeric("noise_floor", &SeriesSettings::noise_floor),
        numeric("min_amplitude", &SeriesSettings::min_amplitude),
        numeric("margin", &SeriesSettings::margin),
        {"require_complete_contact",
         [](const SeriesSettings& s, std::string& out) { out += s.require_complete_contact ? "true" : "false"; },
         [](std::string_view v, SeriesSettings& s) {
             if (v != "true" && v != "false") return false;
             s.require_complete_contact = v == "true";
             return true;
         }},
        word("amplitude", &SeriesSettings::amplitude, {Amplitude::global_scale, Amplitude::z_per_channel}),
        numeric("scale", &SeriesSettings::scale),
        numeric("z_floor", &SeriesSettings::z_floor),
        numeric("max_invalid_fraction", &SeriesSettings::max_invalid_fraction),
        numeric("max_gap", &SeriesSettings::max_gap),
        word("time_axis", &SeriesSettings::time_axis, {TimeAxis::contact, TimeAxis::roll_relative}),
    };
    return k;
}

std::string known_keys() {
    std::string out;
    for (const auto& k : keys()) out += (out.empty() ? "" : ", ") + std::string(k.name);
    return out;
}

}  // namespace

std::string rule_text(const SeriesSettings& settings) {
    std::string out;
    for (const auto& k : keys()) {
        if (!out.empty()) out += ' ';
        out += k.name;
        out += '=';
        k.put(settings, out);
    }
    return out;
}

Result<SeriesSettings> parse_rule_text(std::string_view text, const std::string& source) {
    auto fail = [&source](const std::string& what) {
        return Error{ErrorCode::parse_error, "model file '" + source + "': series_rule: " + what +
                                                 "; train the model again with this rollsense (rollsense train, "
                                                 "rs.analyse) or fix the line (docs/series-preparation.md)"};
    };
    SeriesSettings s;
    std::set<std::string_view> seen;
    while (!text.empty()) {
        const std::size_t end = text.find(' ');
        const std::string_view item = text.substr(0, end);
        text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
        if (item.empty()) continue;  // runs of spaces
        const std::size_t eq = item.find('=');
        if (eq == std::string_view::npos) return fail("'" + std::string(item) + "' is not key=value");
        const std::string_view name = item.substr(0, eq), value = item.substr(eq + 1);
        const Key* key = nullptr;
        for (const auto& k : keys())
            if (k.name == name) key = &k;
        if (!key)
            return fail("unknown setting '" + std::string(name) + "' (this build knows " + known_keys() +
                        "; a model from a newer rollsense needs that version)");
        if (!seen.insert(key->name).second) return fail("setting '" + std::string(name) + "' given twice");
        if (!key->get(value, s)) return fail("setting '" + std::string(name) + "' has a malformed value '" +
                                             std::string(value) + "'");
    }
    if (auto st = validate(s); !st) return fail(st.error().message);
    return s;
}

void describe_series(FeatureTable& table, const SeriesSettings& settings) {
    table.series_length = settings.length;
    table.series_rule = rule_text(settings);
}

Result<ModelRule> model_rule(const Classifier& model, const std::string& source) {
    const std::string text = model.series_rule();
    if (text.empty()) return ModelRule{};
    auto s = parse_rule_text(text, source);
    if (!s) return s.error();
    return ModelRule{*s, true};
}

}  // namespace rollsense::series
