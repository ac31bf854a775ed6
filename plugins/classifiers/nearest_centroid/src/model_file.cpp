// The nearest-centroid model file, in the conventions of every rollsense model
// file (rollsense/model_text.hpp: versioned lines, shortest round-trip numbers,
// counts checked before allocation, a checksum line):
//
//   rollsense-nearest-centroid 1
//   options shrink=0 temperature=1
//   classes K            then K lines "class <training rows> <name>"
//   features P           then P lines "feature <mean> <sd> <name>" (sd 0 = ignored)
//   K lines "centroid <k> <P standardised coordinates>"
//   checksum <FNV-1a 64 of every byte before this line, 16 hex digits>
#include <cmath>

#include "rollsense/model_text.hpp"
#include "rollsense/nearest_centroid/nearest_centroid.hpp"

namespace rollsense::nearest_centroid {
namespace {

using model_text::at_end;
using model_text::keyword;
using model_text::put_number;
using model_text::take;

constexpr std::string_view kMagic = "rollsense-nearest-centroid";
constexpr int kVersion = 1;

}  // namespace

std::string Model::serialize() const {
    std::string out;
    out += std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
    out += "options shrink=";
    put_number(out, options.shrink);
    out += " temperature=";
    put_number(out, options.temperature);
    out += "\nclasses " + std::to_string(class_names.size()) + "\n";
    for (std::size_t c = 0; c < class_names.size(); ++c)
        out += "class " + std::to_string(class_rows[c]) + " " + class_names[c] + "\n";
    out += "features " + std::to_string(feature_names.size()) + "\n";
    for (std::size_t j = 0; j < feature_names.size(); ++j) {
        out += "feature ";
        put_number(out, mean[j]);
        out += ' ';
        put_number(out, sd[j]);
        out += " " + feature_names[j] + "\n";
    }
    const std::size_t p = feature_names.size();
    for (std::size_t c = 0; c < class_names.size(); ++c) {
        out += "centroid " + std::to_string(c);
        for (std::size_t j = 0; j < p; ++j) {
            out += ' ';
            put_number(out, centroids[c * p + j]);
        }
        out += '\n';
    }
    model_text::put_checksum(out);
    return out;
}

Status Model::deserialize(std::string_view text, const std::string& source) {
    model_text::Reader in(text, source);
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
    auto option = [&](std::string_view key, std::string_view value) {
        if (key != "shrink" && key != "temperature") return true;  // informational: a newer writer may add some
        double& v = key == "shrink" ? m.options.shrink : m.options.temperature;
        return take(value, v) && at_end(value) && std::isfinite(v);
    };
    if (auto s = in.options(rest, option); !s) return s;
    if (m.options.shrink < 0.0 || !(m.options.temperature > 0.0))
        return in.fail("options out of range (shrink >= 0, temperature > 0)");

    std::size_t k = 0, p = 0;
    if (auto s = in.count("classes", 100000, k); !s) return s;
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
    if (auto s = in.count("features", 1000000, p); !s) return s;
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
    if (auto s = in.checksum("the last centroid"); !s) return s;
    *this = std::move(m);
    return {};
}

}  // namespace rollsense::nearest_centroid
