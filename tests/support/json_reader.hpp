// A minimal JSON reader for the tests: enough of RFC 8259 to read back what
// rollsense writes (objects, arrays, strings with escapes, numbers, true,
// false, null) and to fail loudly on anything malformed. Numbers are read with
// std::from_chars, so a double written with std::to_chars compares exactly.
#pragma once

#include <charconv>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rollsense::testing {

struct Json {
    using Array = std::vector<Json>;
    using Object = std::map<std::string, Json>;
    std::variant<std::nullptr_t, bool, double, std::string, std::shared_ptr<Array>, std::shared_ptr<Object>> v;

    bool is_null() const { return std::holds_alternative<std::nullptr_t>(v); }
    double num() const { return std::get<double>(v); }
    const std::string& str() const { return std::get<std::string>(v); }
    bool boolean() const { return std::get<bool>(v); }
    const Array& arr() const { return *std::get<std::shared_ptr<Array>>(v); }
    const Object& obj() const { return *std::get<std::shared_ptr<Object>>(v); }
    const Json& operator[](const std::string& key) const {
        const auto& o = obj();
        auto it = o.find(key);
        if (it == o.end()) throw std::runtime_error("JSON object has no member '" + key + "'");
        return it->second;
    }
    const Json& operator[](std::size_t i) const { return arr().at(i); }
    bool has(const std::string& key) const { return obj().count(key) > 0; }
};

class JsonReader {
public:
    static Json parse(std::string_view text) {
        JsonReader r(text);
        Json j = r.value();
        r.ws();
        if (r.i_ != text.size()) r.fail("text after the document");
        return j;
    }

private:
    explicit JsonReader(std::string_view t) : t_(t) {}
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(i_));
    }
    void ws() {
        while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\n' || t_[i_] == '\r' || t_[i_] == '\t')) ++i_;
    }
    char peek() {
        ws();
        if (i_ >= t_.size()) fail("unexpected end");
        return t_[i_];
    }
    void expect(char c) {
        if (peek() != c) fail(std::string("expected '") + c + "'");
        ++i_;
    }
    bool literal(std::string_view word) {
        if (t_.substr(i_, word.size()) != word) return false;
        i_ += word.size();
        return true;
    }
    Json value() {
        const char c = peek();
        if (c == '{') return object();
        if (c == '[') return array();
        if (c == '"') return Json{string()};
        if (literal("true")) return Json{true};
        if (literal("false")) return Json{false};
        if (literal("null")) return Json{nullptr};
        return Json{number()};
    }
    Json object() {
        expect('{');
        auto o = std::make_shared<Json::Object>();
        if (peek() == '}') {
            ++i_;
            return Json{o};
        }
        for (;;) {
            if (peek() != '"') fail("expected a member name");
            std::string k = string();
            expect(':');
            if (!o->emplace(k, value()).second) fail("duplicate member '" + k + "'");
            if (peek() == ',') {
                ++i_;
                continue;
            }
            expect('}');
            return Json{o};
        }
    }
    Json array() {
        expect('[');
        auto a = std::make_shared<Json::Array>();
        if (peek() == ']') {
            ++i_;
            return Json{a};
        }
        for (;;) {
            a->push_back(value());
            if (peek() == ',') {
                ++i_;
                continue;
            }
            expect(']');
            return Json{a};
        }
    }
    std::string string() {
        expect('"');
        std::string out;
        while (i_ < t_.size() && t_[i_] != '"') {
            const char c = t_[i_++];
            if (static_cast<unsigned char>(c) < 0x20) fail("raw control character in a string");
            if (c != '\\') {
                out += c;
                continue;
            }
            if (i_ >= t_.size()) fail("unfinished escape");
            const char e = t_[i_++];
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case '/': out += '/'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'u': {
                    if (i_ + 4 > t_.size()) fail("short \\u escape");
                    unsigned code = 0;
                    auto [p, ec] = std::from_chars(t_.data() + i_, t_.data() + i_ + 4, code, 16);
                    if (ec != std::errc() || p != t_.data() + i_ + 4) fail("bad \\u escape");
                    i_ += 4;
                    if (code >= 0x80) fail("only ASCII \\u escapes are expected from rollsense");
                    out += static_cast<char>(code);
                    break;
                }
                default: fail("unknown escape");
            }
        }
        expect('"');
        return out;
    }
    double number() {
        double d = 0;
        auto [p, ec] = std::from_chars(t_.data() + i_, t_.data() + t_.size(), d);
        if (ec != std::errc()) fail("expected a value");
        i_ = static_cast<std::size_t>(p - t_.data());
        return d;
    }
    std::string_view t_;
    std::size_t i_ = 0;
};

}  // namespace rollsense::testing
