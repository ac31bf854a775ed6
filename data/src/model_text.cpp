#include "rollsense/model_text.hpp"

namespace rollsense::model_text {

void put_checksum(std::string& out) { out += "checksum " + fnv1a_hex(out) + "\n"; }

bool keyword(std::string_view line, std::string_view key, std::string_view& rest) {
    if (line.substr(0, key.size()) != key) return false;
    if (line.size() == key.size()) {
        rest = {};
        return true;
    }
    if (line[key.size()] != ' ') return false;
    rest = line.substr(key.size() + 1);
    return true;
}

bool at_end(std::string_view s) { return s.find_first_not_of(' ') == std::string_view::npos; }

bool Reader::next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    line_start_ = pos_;
    ++line_no_;
    const auto nl = text_.find('\n', pos_);
    if (nl == std::string_view::npos) {
        cut_ = true;
        line = text_.substr(pos_);
        pos_ = text_.size();
    } else {
        line = text_.substr(pos_, nl - pos_);
        pos_ = nl + 1;
    }
    return true;
}

Error Reader::fail(const std::string& what) const {
    if (cut_) return truncated("in the middle of a line");
    return Error{ErrorCode::parse_error, "model file '" + source_ + "' line " + std::to_string(line_no_) + ": " +
                                             what + "; retrain with 'rollsense train'"};  // the way out
}

Error Reader::truncated(const std::string& doing) const {
    return Error{ErrorCode::parse_error, "model file '" + source_ + "' is truncated: it ends after line " +
                                             std::to_string(line_no_) + " while " + doing +
                                             "; save the model again or retrain with 'rollsense train'"};
}

Status Reader::count(std::string_view key, std::size_t max, std::size_t& n) {
    std::string_view line, rest;
    if (!next(line)) return truncated("reading the " + std::string(key) + " count");
    if (!keyword(line, key, rest) || !take(rest, n) || !at_end(rest))
        return fail("expected '" + std::string(key) + " <count>'");
    if (n == 0 || n > max) return fail("implausible " + std::string(key) + " count " + std::to_string(n));
    return {};
}

Status Reader::names(std::string_view key, std::size_t n, std::vector<std::string>& out) {
    out.clear();
    std::string_view line, rest;
    for (std::size_t i = 0; i < n; ++i) {
        if (!next(line)) return truncated("reading the " + std::string(key) + " names");
        if (!keyword(line, key, rest)) return fail("expected '" + std::string(key) + " <name>'");
        out.emplace_back(rest);
    }
    return {};
}

Status Reader::options(std::string_view rest,
                       const std::function<bool(std::string_view, std::string_view)>& option) {
    while (!at_end(rest)) {
        while (rest.front() == ' ') rest.remove_prefix(1);
        const auto word = rest.substr(0, rest.find(' '));
        rest.remove_prefix(word.size());
        const auto eq = word.find('=');
        if (eq == std::string_view::npos) return fail("option '" + std::string(word) + "' is not key=value");
        if (!option(word.substr(0, eq), word.substr(eq + 1)))
            return fail("option '" + std::string(word) + "' has a malformed value");
    }
    return {};
}

Status Reader::checksum(std::string_view after_what) {
    std::string_view line, rest;
    if (!next(line)) return truncated("looking for the checksum line");
    if (!keyword(line, "checksum", rest))
        return fail("expected the 'checksum' line after " + std::string(after_what));
    if (cut_) return truncated("reading the checksum");
    const std::string expected = fnv1a_hex(text_.substr(0, line_start_));
    if (rest != expected)
        return Error{ErrorCode::parse_error, "model file '" + source_ + "' is corrupt: checksum " + std::string(rest) +
                                                 " does not match its content (" + expected +
                                                 "); the file was modified or damaged: retrain with 'rollsense train'"};
    if (next(line)) return fail("unexpected text after the checksum line");
    return {};
}

}  // namespace rollsense::model_text
