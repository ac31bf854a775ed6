#include "rollsense/table_source.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <type_traits>
#include <vector>

namespace rollsense {
namespace {

struct Token {
    char type;  // 'a' name, 'n' number, 's' string, 'p' punctuation
    std::string text;
    int line;
};

// Lua 5.4's tokens, as far as finding table keys needs them: names, numbers,
// strings (quoted and long-bracketed), comments skipped, '==' kept apart from '='.
std::vector<Token> lex(std::string_view s) {
    std::vector<Token> out;
    int line = 1;
    std::size_t i = 0;
    const auto at = [&](std::size_t k) { return k < s.size() ? s[k] : '\0'; };
    // At "[", "[=", "[==": the level of a long bracket, or -1.
    const auto long_level = [&](std::size_t k) {
        std::size_t e = k + 1;
        while (at(e) == '=') ++e;
        return at(k) == '[' && at(e) == '[' ? static_cast<int>(e - k - 1) : -1;
    };
    // Past a long bracket of `level` opened at i; returns where its content ends.
    const auto skip_long = [&](int level) {
        i += static_cast<std::size_t>(level) + 2;
        const std::string close = "]" + std::string(static_cast<std::size_t>(level), '=') + "]";
        const std::size_t end = std::min(s.find(close, i), s.size());
        for (; i < end; ++i) line += s[i] == '\n';
        i = std::min(end + close.size(), s.size());
        return end;
    };
    while (i < s.size()) {
        const char c = s[i];
        const int start_line = line;
        if (c == '\n') {
            ++line, ++i;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else if (c == '-' && at(i + 1) == '-') {
            i += 2;
            if (const int level = long_level(i); level >= 0) skip_long(level);
            else while (i < s.size() && s[i] != '\n') ++i;
        } else if (const int level = c == '[' ? long_level(i) : -1; level >= 0) {
            const std::size_t begin = i + static_cast<std::size_t>(level) + 2;
            const std::size_t end = skip_long(level);
            out.push_back({'s', std::string(s.substr(begin, end - begin)), start_line});
        } else if (c == '"' || c == '\'') {
            std::string text;
            for (++i; i < s.size() && s[i] != c && s[i] != '\n'; ++i) {
                if (s[i] == '\\' && i + 1 < s.size()) text += s[i++];  // kept: an escaped string is no plain literal
                line += s[i] == '\n';
                text += s[i];
            }
            ++i;
            out.push_back({'s', text, start_line});
        } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            const std::size_t b = i;
            while (std::isalnum(static_cast<unsigned char>(at(i))) || at(i) == '_') ++i;
            out.push_back({'a', std::string(s.substr(b, i - b)), start_line});
        } else if (std::isdigit(static_cast<unsigned char>(c)) || (c == '.' && std::isdigit(static_cast<unsigned char>(at(i + 1))))) {
            const std::size_t b = i;
            for (; std::isalnum(static_cast<unsigned char>(at(i))) || at(i) == '.'; ++i)
                if ((at(i + 1) == '-' || at(i + 1) == '+') && std::string_view("eEpP").find(at(i)) != std::string_view::npos) ++i;
            out.push_back({'n', std::string(s.substr(b, i - b)), start_line});
        } else {
            const bool two = at(i + 1) == '=' && std::string_view("=~<>").find(c) != std::string_view::npos;
            out.push_back({'p', std::string(s.substr(i, two ? 2 : 1)), start_line});
            i += two ? 2 : 1;
        }
    }
    return out;
}

bool is(const Token& t, std::string_view p) { return t.type == 'p' && t.text == p; }

}  // namespace

TableSource TableSource::scan(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return TableSource(file.string(), text.str());
}

TableSource::TableSource(std::string file, std::string_view text) : file_(std::move(file)) {
    // One frame per open constructor: the key path it stands at and where in its current field the scan is.
    struct Frame {
        std::string prefix;          // "" for an outermost constructor, "devices.tactile." inside one
        int index = 0;               // positional entries so far
        std::string key;             // the field being read ("" between fields)
        int brackets = 0;            // ( and [ open inside the field's value
        std::vector<Token> value;    // the value's tokens, while it may still be a literal
    };
    std::vector<Frame> open;
    // Key paths are stored whole, so text Lua would still accept (nesting up to
    // its limit under long names, then many fields) could ask for gigabytes:
    // past this budget the scan gives up, and every error names the file only.
    std::size_t path_budget = std::size_t{16} << 20;
    const auto record = [this, &path_budget](const std::string& path, int line) {
        if (path.size() > path_budget) return false;
        path_budget -= path.size();
        auto [it, fresh] = sites_.try_emplace(path, Site{line, 0, {}});
        if (!fresh) it->second = Site{};  // written twice: which one holds the value is not in the text
        return true;
    };
    const auto finish = [this](Frame& f) {  // the field's value ends: keep it when it is a plain literal
        auto it = sites_.find(f.prefix + f.key);
        const auto& v = f.value;
        if (it != sites_.end() && it->second.line > 0) {
            const bool negative = v.size() == 2 && is(v[0], "-") && v[1].type == 'n';
            if (negative) it->second.kind = 'n', it->second.text = "-" + v[1].text;
            else if (v.size() == 1 && (v[0].type == 'n' || v[0].type == 's') && v[0].text.find('\\') == std::string::npos)
                it->second.kind = v[0].type, it->second.text = v[0].text;
            else if (v.size() == 1 && v[0].type == 'a' && (v[0].text == "true" || v[0].text == "false"))
                it->second.kind = 'b', it->second.text = v[0].text;
        }
        f.key.clear(), f.value.clear();
    };
    const auto tokens = lex(text);
    for (std::size_t k = 0; k < tokens.size(); ++k) {
        const Token& t = tokens[k];
        const auto next = [&](std::size_t ahead) { return k + ahead < tokens.size() ? tokens[k + ahead] : Token{'p', "", 0}; };
        if (open.empty()) {
            if (is(t, "{")) open.push_back(Frame{});
            continue;
        }
        Frame& f = open.back();
        if (f.key.empty()) {  // a field starts: `name =`, `["name"] =` or a positional value
            if (is(t, "}")) {
                open.pop_back();
                continue;
            }
            if (is(t, ",") || is(t, ";")) continue;
            if (t.type == 'a' && is(next(1), "=")) {
                f.key = t.text, ++k;
            } else if (is(t, "[") && next(1).type == 's' && is(next(2), "]") && is(next(3), "=")) {
                f.key = next(1).text, k += 3;
            } else {
                f.key = std::to_string(++f.index);
                --k;  // the token is the value's first
            }
            if (!record(f.prefix + f.key, t.line)) {
                sites_.clear();
                return;
            }
            continue;
        }
        if (f.brackets == 0 && (is(t, ",") || is(t, ";") || is(t, "}"))) {
            finish(f);
            if (is(t, "}")) open.pop_back();
            continue;
        }
        if (is(t, "(") || is(t, "[")) ++f.brackets;
        if (is(t, ")") || is(t, "]")) --f.brackets;
        f.value.push_back(t);
        if (is(t, "{")) open.push_back(Frame{f.prefix + f.key + ".", 0, {}, 0, {}});
    }
}

std::string TableSource::where(const std::string& path, const ParamValue* now) const {
    // A key written twice may hold a value set since, elsewhere: not this file's
    // to claim. A value written as an expression (0/0, setting(...)) cannot be
    // compared: it is taken as written (a later statement in another file that
    // changes it is not seen; docs/scripting.md says so).
    const auto holds_value = [](const Site& s, const ParamValue* value) {
        if (!value) return true;
        if (s.kind == 0) return s.line > 0;
        if (s.kind == 's') return std::get_if<std::string>(value) && *std::get_if<std::string>(value) == s.text;
        if (s.kind == 'b') return std::get_if<bool>(value) && (*std::get_if<bool>(value) ? "true" : "false") == s.text;
        const double written = std::strtod(s.text.c_str(), nullptr);
        if (const auto* i = std::get_if<std::int64_t>(value)) return static_cast<double>(*i) == written;
        return std::get_if<double>(value) && *std::get_if<double>(value) == written;
    };
    // A list holds what the file wrote when each entry does, and there are no more of them.
    const auto holds = [&](const Site& s) {
        return std::visit([&](const auto& value) {
            if constexpr (requires { value.size(); typename std::decay_t<decltype(value)>::value_type; } &&
                          !std::is_same_v<std::decay_t<decltype(value)>, std::string>) {
                for (std::size_t i = 0; i < value.size(); ++i) {
                    const ParamValue entry{value[i]};
                    const auto it = sites_.find(path + "." + std::to_string(i + 1));
                    if (it == sites_.end() || !holds_value(it->second, &entry)) return false;
                }
                return sites_.count(path + "." + std::to_string(value.size() + 1)) == 0;
            } else {
                return holds_value(s, now);
            }
        }, now ? *now : ParamValue{false});
    };
    // Not written here (added later to a table of this file, or reached through a name: `hand = hand`), or not
    // the value written here: it came from elsewhere.
    const auto it = sites_.find(path);
    if (it == sites_.end() || (now && !holds(it->second))) return "";
    return it->second.line > 0 ? file_ + ":" + std::to_string(it->second.line) : file_;
}

std::string nearest_site(const std::map<std::string, std::string>& sites, std::string path, const std::string& fallback) {
    for (; !path.empty(); path.resize(path.find('.') == std::string::npos ? 0 : path.rfind('.')))
        if (auto it = sites.find(path); it != sites.end()) return it->second.empty() ? fallback : it->second;
    return fallback;
}

const std::string* key_named_in(std::string_view message, const std::map<std::string, ParamValue>& keys) {
    const auto word = [&](std::size_t i) {
        return i < message.size() && (std::isalnum(static_cast<unsigned char>(message[i])) || message[i] == '_');
    };
    const std::string* first = nullptr;  // the key named first: what the message is about
    std::size_t first_at = std::string_view::npos;
    for (const auto& [key, value] : keys)
        for (auto i = message.find(key); i != std::string_view::npos && i < first_at; i = message.find(key, i + 1))
            if (!word(i - 1) && !word(i + key.size())) first = &key, first_at = i;
    return first;
}

}  // namespace rollsense
