// The nearest-centroid model file, in the conventions of bagged_trees'
// model_file.cpp: versioned, line-oriented text (inspectable, diffable),
// numbers in the shortest form that reads back as the same double (a reloaded
// model predicts exactly what the saved one did), every count checked against
// what follows, and a checksum line that catches truncation and damage.
//
//   rollsense-nearest-centroid 1
//   options shrink=0 temperature=1
//   classes K            then K lines "class <training rows> <name>"
//   features P           then P lines "feature <mean> <sd> <name>" (sd 0 = ignored)
//   K lines "centroid <k> <P standardised coordinates>"
//   checksum <FNV-1a 64 of every byte before this line, 16 hex digits>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "rollsense/checksum.hpp"
#include "rollsense/nearest_centroid/nearest_centroid.hpp"

namespace rollsense::nearest_centroid {
namespace {

constexpr std::string_view kMagic = "rollsense-nearest-centroid";
constexpr int kVersion = 1;

void put(std::string& out, double v) {
    char buf[32];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, ec == std::errc() ? ptr : buf);
}

// The file's lines, each error naming the source and the line number.
class Lines {
public:
    Lines(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

    // The next line; false at the end. A last line without its newline means
    // the file was cut: reported as truncation, whatever the line holds.
    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        const auto nl = text_.find('\n', pos_);
        ++no_;
        start_ = pos_;
        if (nl == std::string_view::npos) {
            cut_ = true;
            line = text_.substr(pos_);
            pos_ = text_.size();
            return true;
        }
        line = text_.substr(pos_, nl - pos_);
        pos_ = nl + 1;
        return true;
    }
    Error fail(const std::string& what) const {
        if (cut_) return truncated("in the middle of a line");
        return Error{ErrorCode::parse_error, "model file '" + source_ + "' line " + std::to_string(no_) + ": " + what +
                                                 "; retrain with 'rollsense train'"};
    }
    Error truncated(const std::string& doing) const {
        return Error{ErrorCode::parse_error, "model file '" + source_ + "' is truncated: it ends after line " +
                                                 std::to_string(no_) + " while " + doing +
                                                 "; save the model again or retrain with 'rollsense train'"};
    }
    std::size_t line_start() const { return start_; }
    bool cut() const { return cut_; }
    // Bytes not read yet: what declared counts are checked against before
    // anything is allocated for them.
    std::size_t remaining() const { return text_.size() - pos_; }

private:
    std::string_view text_;
    std::string source_;
    std::size_t pos_ = 0, start_ = 0, no_ = 0;
    bool cut_ = false;
};

// "<key> <rest>" → rest.
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

// One space-separated number from the front of `s`.
template <class T>
bool take(std::string_view& s, T& out) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    const char* end = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(s.data(), end, out);
    if (ec != std::errc() || (ptr != end && *ptr != ' ')) return false;
    s.remove_prefix(static_cast<std::size_t>(ptr - s.data()));
    return true;
}

bool at_end(std::string_view s) { return s.find_first_not_of(' ') == std::string_view::npos; }

}  // namespace

std::string Model::serialize() const {
    std::string out;
    out += std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
    out += "options shrink=";
    put(out, options.shrink);
    out += " temperature=";
    put(out, options.temperature);
    out += "\nclasses " + std::to_string(class_names.size()) + "\n";
    for (std::size_t c = 0; c < class_names.size(); ++c)
        out += "class " + std::to_string(class_rows[c]) + " " + class_names[c] + "\n";
    out += "features " + std::to_string(feature_names.size()) + "\n";
    for (std::size_t j = 0; j < feature_names.size(); ++j) {
        out += "feature ";
        put(out, mean[j]);
        out += ' ';
        put(out, sd[j]);
        out += " " + feature_names[j] + "\n";
    }
    const std::size_t p = feature_names.size();
    for (std::size_t c = 0; c < class_names.size(); ++c) {
        out += "centroid " + std::to_string(c);
        for (std::size_t j = 0; j < p; ++j) {
            out += ' ';
            put(out, centroids[c * p + j]);
        }
        out += '\n';
    }
    out += "checksum " + fnv1a_hex(out) + "\n";
    return out;
}

Status Model::deserialize(std::string_view text, const std::string& source) {
    Lines in(text, source);
    std::string_view line, rest;
    if (!in.next(line) || !keyword(line, kMagic, rest)) {
        const std::string first(line.substr(0, std::min<std::size_t>(line.size(), 60)));
        const bool other = first.rfind("rollsense-", 0) == 0;
        return Error{ErrorCode::parse_error,
                     "'" + source + "' is not a nearest_centroid model: it should start with '" + std::string(kMagic) +
                         " " + std::to_string(kVersion) + "'" +
                         (other ? ", it starts with '" + first +
                                      "' (a model of another classifier: load it with that classifier's --classifier)"
                                : std::string(first.empty() ? " and is empty" : ""))};
    }
    int version = 0;
    if (!take(rest, version) || !at_end(rest)) return in.fail("malformed format version");
    if (version != kVersion)
        return in.fail("model format version " + std::to_string(version) +
                       " is not supported by this build (it reads version " + std::to_string(kVersion) + ")");

    Model m;
    if (!in.next(line)) return in.truncated("reading the options");
    if (!keyword(line, "options", rest)) return in.fail("expected the 'options' line");
    for (std::string_view words = rest; !at_end(words);) {
        while (words.front() == ' ') words.remove_prefix(1);
        const auto word = words.substr(0, words.find(' '));
        words.remove_prefix(word.size());
        const auto eq = word.find('=');
        if (eq == std::string_view::npos) return in.fail("option '" + std::string(word) + "' is not key=value");
        const auto key = word.substr(0, eq);
        std::string_view value = word.substr(eq + 1);
        double v = 0.0;
        if (key != "shrink" && key != "temperature") continue;  // informational: a newer writer may add some
        if (!take(value, v) || !at_end(value) || !std::isfinite(v))
            return in.fail("option '" + std::string(word) + "' has a malformed value");
        (key == "shrink" ? m.options.shrink : m.options.temperature) = v;
    }
    if (m.options.shrink < 0.0 || !(m.options.temperature > 0.0))
        return in.fail("options out of range (shrink >= 0, temperature > 0)");

    auto count = [&](std::string_view key, std::size_t limit, std::size_t& n) -> Status {
        if (!in.next(line)) return in.truncated("reading the " + std::string(key) + " count");
        if (!keyword(line, key, rest) || !take(rest, n) || !at_end(rest))
            return in.fail("expected '" + std::string(key) + " <count>'");
        if (n == 0 || n > limit) return in.fail("implausible " + std::string(key) + " count " + std::to_string(n));
        return {};
    };
    std::size_t k = 0, p = 0;
    if (auto s = count("classes", 100000, k); !s) return s;
    for (std::size_t c = 0; c < k; ++c) {
        if (!in.next(line)) return in.truncated("reading the class names");
        std::uint64_t rows = 0;
        if (!keyword(line, "class", rest) || !take(rest, rows) || rest.empty())
            return in.fail("expected 'class <training rows> <name>'");
        m.class_rows.push_back(rows);
        m.class_names.emplace_back(rest.substr(1));
    }
    bool any = false;
    for (auto r : m.class_rows) any = any || r > 0;
    if (!any) return in.fail("no class has training rows");
    if (auto s = count("features", 1000000, p); !s) return s;
    for (std::size_t j = 0; j < p; ++j) {
        if (!in.next(line)) return in.truncated("reading the features");
        double f_mean = 0.0, f_sd = 0.0;
        if (!keyword(line, "feature", rest) || !take(rest, f_mean) || !take(rest, f_sd) || rest.empty())
            return in.fail("expected 'feature <mean> <sd> <name>'");
        if (!std::isfinite(f_mean) || !std::isfinite(f_sd) || f_sd < 0.0)
            return in.fail("feature mean or standard deviation is not a finite number (sd >= 0)");
        m.mean.push_back(f_mean);
        m.sd.push_back(f_sd);
        m.feature_names.emplace_back(rest.substr(1));
    }
    // Each coordinate takes at least 2 bytes (" 0"): K x P coordinates the rest
    // of the file cannot hold are refused before the table is allocated
    // (k <= 1e5 and p <= 1e6, so k * p does not overflow).
    if (k * p > in.remaining() / 2)
        return in.fail("declares " + std::to_string(k) + " centroids of " + std::to_string(p) +
                       " coordinates but only " + std::to_string(in.remaining()) + " bytes follow");
    m.centroids.assign(k * p, 0.0);
    for (std::size_t c = 0; c < k; ++c) {
        if (!in.next(line))
            return in.truncated("reading centroid " + std::to_string(c + 1) + " of " + std::to_string(k));
        std::size_t index = 0;
        if (!keyword(line, "centroid", rest) || !take(rest, index)) return in.fail("expected 'centroid <k> ...'");
        if (index != c) return in.fail("centroid " + std::to_string(index) + " where centroid " + std::to_string(c) +
                                       " belongs");
        for (std::size_t j = 0; j < p; ++j)
            if (!take(rest, m.centroids[c * p + j]) || !std::isfinite(m.centroids[c * p + j]))
                return in.fail("expected " + std::to_string(p) + " finite centroid coordinates");
        if (!at_end(rest)) return in.fail("more than " + std::to_string(p) + " centroid coordinates");
    }
    if (!in.next(line)) return in.truncated("looking for the checksum line");
    if (!keyword(line, "checksum", rest)) return in.fail("expected the 'checksum' line after the last centroid");
    if (in.cut()) return in.truncated("reading the checksum");
    const std::string expected = fnv1a_hex(text.substr(0, in.line_start()));
    if (rest != expected)
        return Error{ErrorCode::parse_error, "model file '" + source + "' is corrupt: checksum " + std::string(rest) +
                                                 " does not match its content (" + expected +
                                                 "); the file was modified or damaged: retrain with 'rollsense train'"};
    if (std::string_view extra; in.next(extra)) return in.fail("unexpected text after the checksum line");
    *this = std::move(m);
    return {};
}

}  // namespace rollsense::nearest_centroid
