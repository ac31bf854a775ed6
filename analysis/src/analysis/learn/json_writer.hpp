// A small streaming JSON writer for the files rollsense writes
// (evaluation.json): objects indented one member per line, arrays of scalars
// on one line. Numbers are written with std::to_chars, the shortest text that
// reads back to the same double; NaN and infinities, which JSON cannot hold,
// become null. Strings are escaped (quotes, backslashes, control characters);
// well-formed UTF-8 passes through unchanged, ill-formed bytes become U+FFFD
// (a JSON text is UTF-8), so any bytes a script or a device hands over make valid JSON.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rollsense::learn {

class JsonWriter {
public:
    JsonWriter& begin_object();
    JsonWriter& end_object();
    JsonWriter& begin_array();
    JsonWriter& end_array();
    // Inside an object: the next member's name (then exactly one value or container).
    JsonWriter& key(std::string_view name);

    JsonWriter& value(std::string_view text);
    JsonWriter& value(const char* text) { return value(std::string_view(text)); }
    JsonWriter& value(const std::string& text) { return value(std::string_view(text)); }
    JsonWriter& value(double number);
    JsonWriter& value(std::int64_t number);
    JsonWriter& value(std::uint64_t number);
    JsonWriter& value(int number) { return value(static_cast<std::int64_t>(number)); }
    JsonWriter& value(bool flag);
    JsonWriter& null();

    // The document so far; complete once every container is closed.
    const std::string& str() const { return out_; }
    bool complete() const { return stack_.empty() && !out_.empty(); }

private:
    struct Level {
        bool array = false;
        bool empty = true;
        bool multiline = false;  // an array that holds containers is written one element per line
    };
    void before_value(bool container);
    void newline(std::size_t depth);
    void close(bool array);

    std::string out_;
    std::vector<Level> stack_;
    bool after_key_ = false;
};

// `text` as a JSON string literal, quotes included (ill-formed UTF-8 as U+FFFD).
std::string json_quote(std::string_view text);

}  // namespace rollsense::learn
