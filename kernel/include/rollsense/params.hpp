// Declared, typed plugin parameters.
//
// Every plugin declares its parameters as a schema (name, type, default, range, unit, documentation). The kernel
// checks a profile's table against that schema before the plugin sees it: unknown keys, wrong types and out-of-range
// values are errors naming the profile file and the key, and defaults are filled in. A plugin therefore receives a
// ParamSet in which every declared key exists with the declared type; it never parses strings itself.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense {

enum class ParamType { boolean, integer, number, string, integer_list, number_list, string_list };

std::string_view to_string(ParamType type) noexcept;

using ParamValue = std::variant<bool, std::int64_t, double, std::string, std::vector<std::int64_t>,
                                std::vector<double>, std::vector<std::string>>;

struct ParamSpec {
    std::string name;
    ParamType type = ParamType::number;
    std::string doc;                          // one line, shown by `rollsense plugins`
    std::optional<ParamValue> default_value;  // nullopt = required
    std::optional<double> min;                // inclusive, for numbers and their lists
    std::optional<double> max;
    std::string unit;                         // "deg", "mm", "kPa", ... (documentation)
    std::vector<std::string> choices;         // non-empty: a string must be one of these
};

using ParamSchema = std::vector<ParamSpec>;

// Builder helpers so that a plugin's schema reads like a table.
ParamSpec param_bool(std::string name, std::optional<bool> def, std::string doc);
ParamSpec param_int(std::string name, std::optional<std::int64_t> def, std::string doc,
                    std::optional<double> min = {}, std::optional<double> max = {}, std::string unit = {});
ParamSpec param_number(std::string name, std::optional<double> def, std::string doc,
                       std::optional<double> min = {}, std::optional<double> max = {}, std::string unit = {});
ParamSpec param_string(std::string name, std::optional<std::string> def, std::string doc,
                       std::vector<std::string> choices = {});
ParamSpec param_int_list(std::string name, std::optional<std::vector<std::int64_t>> def, std::string doc,
                         std::optional<double> min = {}, std::optional<double> max = {});
ParamSpec param_number_list(std::string name, std::optional<std::vector<double>> def, std::string doc,
                            std::optional<double> min = {}, std::optional<double> max = {},
                            std::string unit = {});
ParamSpec param_string_list(std::string name, std::optional<std::vector<std::string>> def, std::string doc);

// A validated set of parameter values. Getters throw StatusError(invalid_argument) when a key is missing or has
// another type, which inside a plugin hook the kernel turns into a typed error naming the plugin.
class ParamSet {
public:
    ParamSet() = default;

    void set(const std::string& name, ParamValue value) { values_[name] = std::move(value); }
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    const std::map<std::string, ParamValue>& values() const { return values_; }

    bool get_bool(const std::string& name) const;
    std::int64_t get_int(const std::string& name) const;
    double get_number(const std::string& name) const;  // integers are widened
    const std::string& get_string(const std::string& name) const;
    std::vector<std::int64_t> get_int_list(const std::string& name) const;
    std::vector<double> get_number_list(const std::string& name) const;
    std::vector<std::string> get_string_list(const std::string& name) const;

private:
    const ParamValue& at(const std::string& name) const;
    std::map<std::string, ParamValue> values_;
};

// Check raw values against a schema: fills defaults, rejects unknown keys,
// missing required keys, wrong types, out-of-range numbers and unknown choices.
// `where` names the source for messages, e.g. "share/profiles/sim.lua: devices.tactile".
Result<ParamSet> validate_params(const ParamSchema& schema, const std::map<std::string, ParamValue>& raw,
                                 const std::string& where);

// "3.5", "true", "[1, 2]", "'text'": the form used in messages and listings.
std::string format_param_value(const ParamValue& value);
std::string format_number(double d, int precision = 10);  // "nan", not the "-nan" of Lua's 0/0

}  // namespace rollsense
