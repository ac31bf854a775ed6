#include "rollsense/params.hpp"

#include <cmath>
#include <sstream>
#include <type_traits>

namespace rollsense {

std::string_view to_string(ParamType type) noexcept {
    switch (type) {
        case ParamType::boolean: return "boolean";
        case ParamType::integer: return "integer";
        case ParamType::number: return "number";
        case ParamType::string: return "string";
        case ParamType::integer_list: return "list of integers";
        case ParamType::number_list: return "list of numbers";
        case ParamType::string_list: return "list of strings";
    }
    return "?";
}

namespace {

ParamSpec make_spec(std::string name, ParamType type, std::optional<ParamValue> def, std::string doc,
                    std::optional<double> min, std::optional<double> max, std::string unit) {
    return {std::move(name), type, std::move(doc), std::move(def), min, max, std::move(unit), {}};
}

template <class T>
std::optional<ParamValue> wrap(const std::optional<T>& v) {
    if (!v) return std::nullopt;
    return ParamValue{*v};
}

// ParamValue's alternatives come in ParamType's order.
static_assert(std::is_same_v<std::variant_alternative_t<std::size_t(ParamType::string_list), ParamValue>,
                             std::vector<std::string>>);
std::string value_type_name(const ParamValue& v) { return std::string(to_string(static_cast<ParamType>(v.index()))); }

// Convert a raw value to the declared type where the conversion loses nothing (an integer where a number is expected,
// an integer list for a number list, an empty list of any kind). Anything else is a type error.
std::optional<ParamValue> coerce(const ParamValue& v, ParamType type) {
    switch (type) {
        case ParamType::boolean:
            if (auto* b = std::get_if<bool>(&v)) return ParamValue{*b};
            return std::nullopt;
        case ParamType::integer:
            if (auto* i = std::get_if<std::int64_t>(&v)) return ParamValue{*i};
            if (auto* d = std::get_if<double>(&v); d && std::floor(*d) == *d && std::abs(*d) < 9e15)
                return ParamValue{static_cast<std::int64_t>(*d)};
            return std::nullopt;
        case ParamType::number:
            if (auto* d = std::get_if<double>(&v)) return ParamValue{*d};
            if (auto* i = std::get_if<std::int64_t>(&v)) return ParamValue{static_cast<double>(*i)};
            return std::nullopt;
        case ParamType::string:
            if (auto* s = std::get_if<std::string>(&v)) return ParamValue{*s};
            return std::nullopt;
        case ParamType::integer_list:
            if (auto* l = std::get_if<std::vector<std::int64_t>>(&v)) return ParamValue{*l};
            if (auto* l = std::get_if<std::vector<double>>(&v)) {
                std::vector<std::int64_t> out;
                for (double d : *l) {
                    if (std::floor(d) != d) return std::nullopt;
                    out.push_back(static_cast<std::int64_t>(d));
                }
                return ParamValue{out};
            }
            if (auto* l = std::get_if<std::vector<std::string>>(&v); l && l->empty())
                return ParamValue{std::vector<std::int64_t>{}};
            return std::nullopt;
        case ParamType::number_list:
            if (auto* l = std::get_if<std::vector<double>>(&v)) return ParamValue{*l};
            if (auto* l = std::get_if<std::vector<std::int64_t>>(&v))
                return ParamValue{std::vector<double>(l->begin(), l->end())};
            if (auto* l = std::get_if<std::vector<std::string>>(&v); l && l->empty())
                return ParamValue{std::vector<double>{}};
            return std::nullopt;
        case ParamType::string_list:
            if (auto* l = std::get_if<std::vector<std::string>>(&v)) return ParamValue{*l};
            if (auto* l = std::get_if<std::vector<std::int64_t>>(&v); l && l->empty())
                return ParamValue{std::vector<std::string>{}};
            if (auto* l = std::get_if<std::vector<double>>(&v); l && l->empty())
                return ParamValue{std::vector<std::string>{}};
            return std::nullopt;
    }
    return std::nullopt;
}

std::string with_article(std::string_view noun) {
    const bool vowel = !noun.empty() && std::string_view("aeiou").find(noun[0]) != std::string_view::npos;
    return (vowel ? "an " : "a ") + std::string(noun);
}

std::optional<std::string> check_range(const ParamSpec& spec, double x) {
    // A declared range takes finite numbers only: NaN would pass `<` and `>`, infinity a one-sided range.
    if (((spec.min || spec.max) && !std::isfinite(x)) || x < spec.min.value_or(x) || x > spec.max.value_or(x)) {
        std::string range = "[" + (spec.min ? format_number(*spec.min) : std::string("-inf")) + ", " +
                            (spec.max ? format_number(*spec.max) : std::string("inf")) + "]";
        return format_number(x) + (std::isfinite(x) ? " is outside" : " is not a finite number in") + " the allowed range " + range +
               (spec.unit.empty() ? "" : " " + spec.unit);
    }
    return std::nullopt;
}

}  // namespace

ParamSpec param_bool(std::string name, std::optional<bool> def, std::string doc) {
    return make_spec(std::move(name), ParamType::boolean, wrap(def), std::move(doc), {}, {}, {});
}
ParamSpec param_int(std::string name, std::optional<std::int64_t> def, std::string doc, std::optional<double> min,
                    std::optional<double> max, std::string unit) {
    return make_spec(std::move(name), ParamType::integer, wrap(def), std::move(doc), min, max, std::move(unit));
}
ParamSpec param_number(std::string name, std::optional<double> def, std::string doc, std::optional<double> min,
                       std::optional<double> max, std::string unit) {
    return make_spec(std::move(name), ParamType::number, wrap(def), std::move(doc), min, max, std::move(unit));
}
ParamSpec param_string(std::string name, std::optional<std::string> def, std::string doc,
                       std::vector<std::string> choices) {
    auto s = make_spec(std::move(name), ParamType::string, wrap(def), std::move(doc), {}, {}, {});
    s.choices = std::move(choices);
    return s;
}
ParamSpec param_int_list(std::string name, std::optional<std::vector<std::int64_t>> def, std::string doc,
                         std::optional<double> min, std::optional<double> max) {
    return make_spec(std::move(name), ParamType::integer_list, wrap(def), std::move(doc), min, max, {});
}
ParamSpec param_number_list(std::string name, std::optional<std::vector<double>> def, std::string doc,
                            std::optional<double> min, std::optional<double> max, std::string unit) {
    return make_spec(std::move(name), ParamType::number_list, wrap(def), std::move(doc), min, max, std::move(unit));
}
ParamSpec param_string_list(std::string name, std::optional<std::vector<std::string>> def, std::string doc) {
    return make_spec(std::move(name), ParamType::string_list, wrap(def), std::move(doc), {}, {}, {});
}

const ParamValue& ParamSet::at(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end())
        throw StatusError(Status(ErrorCode::plugin_error, "parameter '" + name + "' has no value (undeclared, or optional "
                                                      "and not given: has() first): a bug of the code reading it"));
    return it->second;
}

namespace {  // the values were checked against the schema: another type asked is the reader's bug
template <class T> const T& typed(const ParamValue& v, const std::string& name, const char* want) {
    if (auto* p = std::get_if<T>(&v)) return *p;
    throw StatusError(Status(ErrorCode::plugin_error, "parameter '" + name + "' is " + with_article(value_type_name(v)) + ", read as a " +
                                                          want + ": a bug of the code reading it, not of the profile"));
}
}  // namespace

bool ParamSet::get_bool(const std::string& name) const { return typed<bool>(at(name), name, "boolean"); }
std::int64_t ParamSet::get_int(const std::string& name) const { return typed<std::int64_t>(at(name), name, "integer"); }
double ParamSet::get_number(const std::string& name) const {
    const auto& v = at(name);
    if (auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
    return typed<double>(v, name, "number");
}
const std::string& ParamSet::get_string(const std::string& name) const {
    return typed<std::string>(at(name), name, "string");
}
std::vector<std::int64_t> ParamSet::get_int_list(const std::string& name) const {
    return typed<std::vector<std::int64_t>>(at(name), name, "list of integers");
}
std::vector<double> ParamSet::get_number_list(const std::string& name) const {
    const auto& v = at(name);
    if (auto* l = std::get_if<std::vector<std::int64_t>>(&v)) return {l->begin(), l->end()};
    return typed<std::vector<double>>(v, name, "list of numbers");
}
std::vector<std::string> ParamSet::get_string_list(const std::string& name) const {
    return typed<std::vector<std::string>>(at(name), name, "list of strings");
}

Result<ParamSet> validate_params(const ParamSchema& schema, const std::map<std::string, ParamValue>& raw,
                                 const std::string& where) {
    ParamSet out;
    for (const auto& [key, value] : raw) {
        const ParamSpec* spec = nullptr;
        for (const auto& s : schema)
            if (s.name == key) spec = &s;
        if (!spec) {
            std::string known;
            for (const auto& s : schema) known += (known.empty() ? "" : ", ") + s.name;
            return Error{ErrorCode::invalid_argument,
                         where + ": unknown key '" + key + "' (known keys: " + (known.empty() ? "none" : known) + ")"};
        }
        auto coerced = coerce(value, spec->type);
        if (!coerced)
            return Error{ErrorCode::invalid_argument, where + ": key '" + key + "' must be " +
                                                          with_article(to_string(spec->type)) + ", got " +
                                                          with_article(value_type_name(value)) + " (" +
                                                          format_param_value(value) + ")" +
                                                          (spec->type == ParamType::string && value.index() <= 2 ? "; in double quotes it is text (\"" + format_param_value(value) +
                                                                                             "\"; --set and --classifier read a number where they can: --set 'KEY=\"" + format_param_value(value) + "\"')" : "")};
        std::optional<std::string> range_error;  // of the first number (of a number, an integer or a list) out of range
        std::visit([&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::int64_t>) range_error = check_range(*spec, double(v));
            if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<std::int64_t>>)
                for (auto x : v) range_error = range_error ? range_error : check_range(*spec, double(x));
        }, *coerced);
        if (range_error) return Error{ErrorCode::invalid_argument, where + ": key '" + key + "': " + *range_error};
        if (auto* s = std::get_if<std::string>(&*coerced); s && !spec->choices.empty()) {
            bool found = false;
            std::string list;
            for (const auto& c : spec->choices) {
                found = found || c == *s;
                list += (list.empty() ? "" : ", ") + c;
            }
            if (!found)
                return Error{ErrorCode::invalid_argument,
                             where + ": key '" + key + "' is '" + *s + "', expected one of: " + list};
        }
        out.set(key, std::move(*coerced));
    }
    for (const auto& spec : schema) {
        if (out.has(spec.name)) continue;
        if (!spec.default_value)
            return Error{ErrorCode::invalid_argument, where + ": required key '" + spec.name + "' is missing (" +
                                                          std::string(to_string(spec.type)) + ": " + spec.doc + ")"};
        out.set(spec.name, *spec.default_value);
    }
    return out;
}

namespace {
struct ValueFormatter {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(double d) const { return format_number(d); }
    std::string operator()(const std::string& s) const { return "'" + s + "'"; }
    template <class T>
    std::string operator()(const std::vector<T>& l) const {
        std::string out = "{";
        for (std::size_t i = 0; i < l.size(); ++i) out += (i ? ", " : "") + (*this)(l[i]);
        return out + "}";
    }
};
}  // namespace

std::string format_param_value(const ParamValue& value) { return std::visit(ValueFormatter{}, value); }

std::string format_number(double d, int precision) {
    std::ostringstream os;
    os.precision(precision);
    os << (std::isnan(d) ? std::fabs(d) : d);
    return os.str();
}

}  // namespace rollsense
