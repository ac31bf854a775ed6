#include "analysis/learn/json_writer.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace rollsense::learn {

namespace {

// The length of the well-formed UTF-8 sequence that `s` starts with (1 to 4
// bytes), or minus the length of its maximal ill-formed subpart: the bytes
// that one U+FFFD replaces (Unicode §3.9, "U+FFFD substitution of maximal
// subparts": a stray byte, a truncated sequence, an overlong form, a
// surrogate, a code point above U+10FFFF).
int utf8_sequence(std::string_view s) {
    const auto lead = static_cast<unsigned char>(s[0]);
    if (lead < 0x80) return 1;
    int trail = 0;
    unsigned char low = 0x80, high = 0xBF;  // the range of the first trailing byte
    if (lead >= 0xC2 && lead <= 0xDF) {
        trail = 1;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        trail = 2;
        if (lead == 0xE0) low = 0xA0;   // not overlong
        if (lead == 0xED) high = 0x9F;  // not a surrogate
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        trail = 3;
        if (lead == 0xF0) low = 0x90;   // not overlong
        if (lead == 0xF4) high = 0x8F;  // at most U+10FFFF
    } else {
        return -1;
    }
    for (int k = 1; k <= trail; ++k) {
        if (static_cast<std::size_t>(k) >= s.size()) return -k;
        const auto c = static_cast<unsigned char>(s[static_cast<std::size_t>(k)]);
        if (c < (k == 1 ? low : 0x80) || c > (k == 1 ? high : 0xBF)) return -k;
    }
    return trail + 1;
}

}  // namespace

std::string json_quote(std::string_view text) {
    std::string out = "\"";
    for (std::size_t i = 0; i < text.size();) {
        const char ch = text[i];
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 0x80) {  // JSON is UTF-8 (RFC 8259 §8.1): bytes that are not become U+FFFD
            const int n = utf8_sequence(text.substr(i));
            if (n > 0)
                out.append(text.substr(i, static_cast<std::size_t>(n)));
            else
                out += "\xEF\xBF\xBD";
            i += static_cast<std::size_t>(n > 0 ? n : -n);
            continue;
        }
        ++i;
        switch (ch) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            case '\b': out += "\\b"; break;
            case '\f': out += "\\f"; break;
            default:
                if (c < 0x20) {
                    static const char* hex = "0123456789abcdef";
                    out += "\\u00";
                    out += hex[c >> 4];
                    out += hex[c & 0xf];
                } else {
                    out += ch;
                }
        }
    }
    out += '"';
    return out;
}

void JsonWriter::newline(std::size_t depth) {
    out_ += '\n';
    out_.append(2 * depth, ' ');
}

// Misuse (a value without a key in an object, a key in an array) is a bug in
// the caller, not a condition of the data: it throws.
void JsonWriter::before_value(bool container) {
    if (stack_.empty()) {
        if (!out_.empty()) throw std::logic_error("JsonWriter: a second top-level value");
        return;
    }
    Level& top = stack_.back();
    if (!top.array) {
        if (!after_key_) throw std::logic_error("JsonWriter: a value inside an object needs a key first");
        after_key_ = false;
        return;
    }
    if (!top.empty) out_ += container || top.multiline ? "," : ", ";
    if (container) top.multiline = true;
    if (top.multiline) newline(stack_.size());
    top.empty = false;
}

JsonWriter& JsonWriter::key(std::string_view name) {
    if (stack_.empty() || stack_.back().array || after_key_)
        throw std::logic_error("JsonWriter: key '" + std::string(name) + "' outside an object");
    Level& top = stack_.back();
    if (!top.empty) out_ += ',';
    newline(stack_.size());
    top.empty = false;
    out_ += json_quote(name);
    out_ += ": ";
    after_key_ = true;
    return *this;
}

JsonWriter& JsonWriter::begin_object() {
    before_value(true);
    out_ += '{';
    stack_.push_back({false, true, true});
    return *this;
}

JsonWriter& JsonWriter::begin_array() {
    before_value(true);
    out_ += '[';
    stack_.push_back({true, true, false});
    return *this;
}

void JsonWriter::close(bool array) {
    if (stack_.empty() || stack_.back().array != array || after_key_)
        throw std::logic_error(array ? "JsonWriter: end_array without its begin_array"
                                     : "JsonWriter: end_object without its begin_object");
    const Level top = stack_.back();
    stack_.pop_back();
    if (!top.empty && top.multiline) newline(stack_.size());
    out_ += array ? ']' : '}';
}

JsonWriter& JsonWriter::end_object() {
    close(false);
    return *this;
}

JsonWriter& JsonWriter::end_array() {
    close(true);
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view text) {
    before_value(false);
    out_ += json_quote(text);
    return *this;
}

JsonWriter& JsonWriter::value(double number) {
    if (!std::isfinite(number)) return null();
    before_value(false);
    char buf[64];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, number);
    out_.append(buf, ec == std::errc() ? end : buf);
    return *this;
}

JsonWriter& JsonWriter::value(std::int64_t number) {
    before_value(false);
    out_ += std::to_string(number);
    return *this;
}

JsonWriter& JsonWriter::value(std::uint64_t number) {
    before_value(false);
    out_ += std::to_string(number);
    return *this;
}

JsonWriter& JsonWriter::value(bool flag) {
    before_value(false);
    out_ += flag ? "true" : "false";
    return *this;
}

JsonWriter& JsonWriter::null() {
    before_value(false);
    out_ += "null";
    return *this;
}

}  // namespace rollsense::learn
