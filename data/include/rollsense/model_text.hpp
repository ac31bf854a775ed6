// The line-oriented text of rollsense's classifier model files (bagged_trees,
// nearest_centroid, minirocket): one reader, so every model format checks its
// lines, counts and checksum the same way.
//
// The shared conventions: a versioned first line "<magic> <version>"; one
// record per line, "<keyword> <values…>"; numbers in the shortest form that
// reads back as the same value (a reloaded model predicts exactly what the
// saved one did); every declared count checked against the bytes that follow
// before anything is allocated for it; and a last line
// "checksum <fnv1a_hex of every byte before it>" that catches truncation and
// damage. Every error names the file and the line, and says what to do.
#pragma once

#include <charconv>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "rollsense/checksum.hpp"
#include "rollsense/status.hpp"

namespace rollsense::model_text {

// Appends `v` in the shortest form that reads back as the same value.
template <class T>
void put_number(std::string& out, T v) {
    char buf[40];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, ec == std::errc() ? ptr : buf);
}

// Appends the checksum line over everything in `out` so far.
void put_checksum(std::string& out);

// "<key> <rest>" → true with `rest`; a line that is exactly `key` gives an empty rest.
bool keyword(std::string_view line, std::string_view key, std::string_view& rest);

// One space-separated number from the front of `s` (leading spaces skipped).
template <class T>
bool take(std::string_view& s, T& out) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    const char* end = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(s.data(), end, out);
    if (ec != std::errc() || (ptr != end && *ptr != ' ')) return false;
    s.remove_prefix(static_cast<std::size_t>(ptr - s.data()));
    return true;
}

// Nothing but spaces left.
bool at_end(std::string_view s);

class Reader {
public:
    Reader(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

    // The next line; false at the end. A last line without its newline means
    // the file was cut: any error on it is reported as truncation.
    bool next(std::string_view& line);

    Error fail(const std::string& what) const;          // "model file 'F' line N: what"
    Error truncated(const std::string& doing) const;    // "… is truncated: it ends after line N while doing"

    // "<key> <count>" with 1 <= count <= max.
    Status count(std::string_view key, std::size_t max, std::size_t& n);
    // `n` lines "<key> <name>".
    Status names(std::string_view key, std::size_t n, std::vector<std::string>& out);
    // The words "key=value" of an options line, each handed to `option`,
    // which returns false for a malformed value (unknown keys are its to ignore).
    Status options(std::string_view rest, const std::function<bool(std::string_view, std::string_view)>& option);
    // The checksum line, checked against every byte before it, and nothing after it.
    Status checksum(std::string_view after_what);

    // Bytes not read yet: what declared counts are checked against before
    // anything is allocated for them.
    std::size_t remaining() const { return text_.size() - pos_; }

private:
    std::string_view text_;
    std::string source_;
    std::size_t pos_ = 0, line_start_ = 0, line_no_ = 0;
    bool cut_ = false;
};

}  // namespace rollsense::model_text
