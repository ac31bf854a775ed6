// The MiniRocket model file, in the bagged-trees conventions: versioned,
// line-oriented text (inspectable, diffable), numbers in the shortest form that
// reads back to the same value, every count checked before anything is
// allocated, and an FNV-1a checksum line catching truncation and damage.
//
//   rollsense-minirocket 1
//   classes K            then K lines "class <name>"
//   channels C           then C lines "channel <name>"
//   series_length L
//   options num_features=9996 max_dilations_per_kernel=32 seed=1 alpha_log10_low=-3 alpha_log10_high=3 alphas=10
//   alpha <chosen α>
//   combinations M       then M lines: the channel subset of each (dilation, kernel), dilation-major
//   features P           then P lines "<bias> <mean> <scale> <weight class 0> … <weight class K−1>"
//   intercept <K values>
//   checksum <FNV-1a 64 of every byte before this line, 16 hex digits>
//
// Dilations, feature counts and padding are not stored: they follow from L
// and the options, and are recomputed (and checked against M and P) on load.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "rollsense/checksum.hpp"
#include "rollsense/minirocket/minirocket.hpp"

namespace rollsense::minirocket {
namespace {

constexpr const char* kMagic = "rollsense-minirocket";
constexpr int kVersion = 1;

template <class T>
void put(std::string& out, T v) {
    char buf[40];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, ec == std::errc() ? ptr : buf);
}

template <class T>
bool take(std::string_view& s, T& out) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec != std::errc() || (ptr != s.data() + s.size() && *ptr != ' ')) return false;
    s.remove_prefix(static_cast<std::size_t>(ptr - s.data()));
    return true;
}

bool at_end(std::string_view s) { return s.find_first_not_of(' ') == std::string_view::npos; }

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

// Line reader whose errors name the file and line and say what to do.
class Reader {
public:
    Reader(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}
    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        start_ = pos_;
        const auto nl = text_.find('\n', pos_);
        ++line_no_;
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
    Error fail(const std::string& what) const {
        if (cut_) return truncated("in the middle of a line");
        return Error{ErrorCode::parse_error,
                     "model file '" + source_ + "' line " + std::to_string(line_no_) + ": " + what};
    }
    Error truncated(const std::string& doing) const {
        return Error{ErrorCode::parse_error, "model file '" + source_ + "' is truncated: it ends after line " +
                                                 std::to_string(line_no_) + " while " + doing +
                                                 "; save the model again or retrain with 'rollsense train'"};
    }
    std::size_t start() const { return start_; }
    bool cut() const { return cut_; }
    // Bytes not read yet: what declared counts are checked against before
    // anything is allocated for them.
    std::size_t remaining() const { return text_.size() - pos_; }

private:
    std::string_view text_;
    std::string source_;
    std::size_t pos_ = 0, start_ = 0, line_no_ = 0;
    bool cut_ = false;
};

}  // namespace

std::string Model::serialize(const Options& o) const {
    std::string out;
    out += std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
    out += "classes " + std::to_string(class_names.size()) + "\n";
    for (const auto& c : class_names) out += "class " + c + "\n";
    out += "channels " + std::to_string(channel_names.size()) + "\n";
    for (const auto& c : channel_names) out += "channel " + c + "\n";
    out += "series_length " + std::to_string(transform.length()) + "\n";
    const auto& t = transform.options();
    out += "options num_features=" + std::to_string(t.num_features) +
           " max_dilations_per_kernel=" + std::to_string(t.max_dilations_per_kernel) +
           " seed=" + std::to_string(t.seed) + " alpha_log10_low=";
    put(out, o.log10_alpha_low);
    out += " alpha_log10_high=";
    put(out, o.log10_alpha_high);
    out += " alphas=" + std::to_string(o.alphas) + "\n";
    out += "alpha ";
    put(out, alpha);
    out += "\n";
    out += "combinations " + std::to_string(transform.combinations().size()) + "\n";
    for (const auto& c : transform.combinations()) {
        for (std::size_t i = 0; i < c.channels.size(); ++i) {
            if (i) out += ' ';
            out += std::to_string(c.channels[i]);
        }
        out += '\n';
    }
    const std::size_t p = transform.features(), k = classes();
    out += "features " + std::to_string(p) + "\n";
    for (std::size_t j = 0; j < p; ++j) {
        put(out, transform.biases()[j]);
        out += ' ';
        put(out, mean[j]);
        out += ' ';
        put(out, scale[j]);
        for (std::size_t c = 0; c < k; ++c) {
            out += ' ';
            put(out, weights[j * k + c]);
        }
        out += '\n';
    }
    out += "intercept";
    for (double v : intercept) {
        out += ' ';
        put(out, v);
    }
    out += "\n";
    out += "checksum " + fnv1a_hex(out) + "\n";
    return out;
}

Status Model::deserialize(std::string_view text, const std::string& source, Options& options) {
    Reader in(text, source);
    std::string_view line, rest;
    if (!in.next(line) || !keyword(line, kMagic, rest))
        return Error{ErrorCode::parse_error, "'" + source + "' is not a rollsense MiniRocket model (it should start with '" +
                                                 kMagic + " " + std::to_string(kVersion) +
                                                 "'); is it another classifier's model? load it with that classifier"};
    int version = 0;
    if (!take(rest, version) || !at_end(rest)) return in.fail("malformed format version");
    if (version > kVersion)
        return in.fail("model format version " + std::to_string(version) + " is newer than this build reads (" +
                       std::to_string(kVersion) + "); update rollsense or retrain with 'rollsense train'");
    if (version != kVersion) return in.fail("model format version " + std::to_string(version) + " is not supported");

    auto count = [&](std::string_view key, std::size_t& n, std::size_t max, const char* doing) -> Status {
        if (!in.next(line)) return in.truncated(doing);
        if (!keyword(line, key, rest) || !take(rest, n) || !at_end(rest))
            return in.fail("expected '" + std::string(key) + " <count>'");
        if (n == 0 || n > max) return in.fail("implausible " + std::string(key) + " " + std::to_string(n));
        return {};
    };
    auto names = [&](std::string_view key, std::size_t n, std::vector<std::string>& out) -> Status {
        for (std::size_t i = 0; i < n; ++i) {
            if (!in.next(line)) return in.truncated("reading the " + std::string(key) + " names");
            if (!keyword(line, key, rest)) return in.fail("expected '" + std::string(key) + " <name>'");
            out.emplace_back(rest);
        }
        return {};
    };

    Model m;
    std::size_t k = 0, channels = 0, length = 0, combos = 0, p = 0;
    if (auto s = count("classes", k, 100000, "reading the class count"); !s) return s;
    if (k < 2) return in.fail("a model needs at least 2 classes");
    if (auto s = names("class", k, m.class_names); !s) return s;
    if (auto s = count("channels", channels, 100000, "reading the channel count"); !s) return s;
    if (auto s = names("channel", channels, m.channel_names); !s) return s;
    if (auto s = count("series_length", length, 10000000, "reading the series length"); !s) return s;

    Options o = options;
    if (!in.next(line)) return in.truncated("reading the options");
    if (!keyword(line, "options", rest)) return in.fail("expected the 'options' line");
    {
        std::istringstream words{std::string(rest)};
        std::string word;
        while (words >> word) {
            const auto eq = word.find('=');
            if (eq == std::string::npos) return in.fail("option '" + word + "' is not key=value");
            const std::string key = word.substr(0, eq);
            std::string_view v = std::string_view(word).substr(eq + 1);
            bool ok = true;
            if (key == "num_features") ok = take(v, o.transform.num_features);
            else if (key == "max_dilations_per_kernel") ok = take(v, o.transform.max_dilations_per_kernel);
            else if (key == "seed") ok = take(v, o.transform.seed);
            else if (key == "alpha_log10_low") ok = take(v, o.log10_alpha_low);
            else if (key == "alpha_log10_high") ok = take(v, o.log10_alpha_high);
            else if (key == "alphas") ok = take(v, o.alphas);
            // unknown keys are informational: a newer writer may add some
            if (!ok) return in.fail("option '" + word + "' has a malformed value");
        }
    }
    if (o.transform.num_features < kKernels || o.transform.num_features > 1000000 ||
        o.transform.max_dilations_per_kernel < 1 || o.transform.max_dilations_per_kernel > 1024)
        return in.fail("options out of range (num_features 84…1,000,000, max_dilations_per_kernel 1…1024)");

    if (!in.next(line)) return in.truncated("reading the chosen alpha");
    if (!keyword(line, "alpha", rest) || !take(rest, m.alpha) || !at_end(rest) || !(m.alpha > 0.0))
        return in.fail("expected 'alpha <positive number>'");

    if (auto s = m.transform.plan(channels, length, o.transform); !s) return in.fail(s.error().message);
    if (auto s = count("combinations", combos, 10000000, "reading the combination count"); !s) return s;
    if (combos != m.transform.combinations().size())
        return in.fail(std::to_string(combos) + " combinations where the options and series length give " +
                       std::to_string(m.transform.combinations().size()));
    // One line of at least 2 bytes per combination, and per feature a line of
    // 3 + K numbers of at least 2 bytes each: counts the rest of the file
    // cannot hold are refused before anything is allocated for them.
    if (combos > in.remaining() / 2)
        return in.fail("declares " + std::to_string(combos) + " combinations but only " +
                       std::to_string(in.remaining()) + " bytes follow");
    std::vector<std::vector<int>> subsets(combos);
    for (auto& sub : subsets) {
        if (!in.next(line)) return in.truncated("reading the channel subsets");
        rest = line;
        while (!at_end(rest)) {
            int ch = -1;
            if (!take(rest, ch) || ch < 0 || static_cast<std::size_t>(ch) >= channels || sub.size() >= channels)
                return in.fail("expected channel indices below " + std::to_string(channels));
            sub.push_back(ch);
        }
    }
    if (auto s = count("features", p, 10000000, "reading the feature count"); !s) return s;
    if (p != m.transform.features())
        return in.fail(std::to_string(p) + " features where the options and series length give " +
                       std::to_string(m.transform.features()));
    if (p > in.remaining() / (2 * (3 + k)))  // k <= 1e5, so 2 * (3 + k) cannot overflow
        return in.fail("declares " + std::to_string(p) + " features of " + std::to_string(k) +
                       " weights each but only " + std::to_string(in.remaining()) + " bytes follow");
    std::vector<float> biases(p);
    m.mean.resize(p);
    m.scale.resize(p);
    m.weights.resize(p * k);
    for (std::size_t j = 0; j < p; ++j) {
        if (!in.next(line)) return in.truncated("reading feature " + std::to_string(j + 1) + " of " + std::to_string(p));
        rest = line;
        bool ok = take(rest, biases[j]) && take(rest, m.mean[j]) && take(rest, m.scale[j]) && m.scale[j] > 0.0f;
        for (std::size_t c = 0; ok && c < k; ++c) ok = take(rest, m.weights[j * k + c]) && std::isfinite(m.weights[j * k + c]);
        if (!ok || !at_end(rest) || !std::isfinite(biases[j]) || !std::isfinite(m.mean[j]))
            return in.fail("expected '<bias> <mean> <scale > 0> and " + std::to_string(k) + " finite weights'");
    }
    if (auto s = m.transform.restore(std::move(subsets), std::move(biases)); !s) return in.fail(s.error().message);
    if (!in.next(line)) return in.truncated("reading the intercepts");
    if (!keyword(line, "intercept", rest)) return in.fail("expected the 'intercept' line");
    m.intercept.resize(k);
    for (auto& v : m.intercept)
        if (!take(rest, v) || !std::isfinite(v)) return in.fail("expected " + std::to_string(k) + " finite intercepts");
    if (!at_end(rest)) return in.fail("more than " + std::to_string(k) + " intercepts");

    if (!in.next(line)) return in.truncated("looking for the checksum line");
    if (!keyword(line, "checksum", rest)) return in.fail("expected the 'checksum' line");
    const std::string expected = fnv1a_hex(text.substr(0, in.start()));
    if (in.cut()) return in.truncated("reading the checksum");
    if (rest != expected)
        return Error{ErrorCode::parse_error, "model file '" + source + "' is corrupt: checksum " + std::string(rest) +
                                                 " does not match its content (" + expected +
                                                 "); the file was modified or damaged — retrain with 'rollsense train'"};
    *this = std::move(m);
    options.transform = o.transform;
    options.log10_alpha_low = o.log10_alpha_low;
    options.log10_alpha_high = o.log10_alpha_high;
    options.alphas = o.alphas;
    return {};
}

}  // namespace rollsense::minirocket
