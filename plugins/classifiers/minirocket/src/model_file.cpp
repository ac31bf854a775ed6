// The MiniRocket model file, in the conventions of every rollsense model file
// (rollsense/model_text.hpp: versioned lines, shortest round-trip numbers,
// counts checked before allocation, a checksum line):
//
//   rollsense-minirocket 2
//   classes K            then K lines "class <name>"
//   channels C           then C lines "channel <name>"
//   series_length L
//   series_rule <how the series were prepared>   (version 2; the rest of the line, possibly empty)
//   options num_features=9996 max_dilations_per_kernel=32 seed=1 alpha_log10_low=-3 alpha_log10_high=3 alphas=10
//   alpha <chosen α>
//   combinations M       then M lines: the channel subset of each (dilation, kernel), dilation-major
//   features P           then P lines "<bias> <mean> <scale> <weight class 0> … <weight class K−1>"
//   intercept <K values>
//   checksum <FNV-1a 64 of every byte before this line, 16 hex digits>
//
// Dilations, feature counts and padding are not stored: they follow from L
// and the options, and are recomputed (and checked against M and P) on load.
//
// Version 2 added the series_rule line (FeatureTable::series_rule: the series
// rule's settings, written and read by the analysis layer, opaque here).
// Version 1 files, which lack it, still load with an empty rule; a version 1
// reader refuses version 2 files as newer than it reads.
#include <cmath>

#include "rollsense/model_text.hpp"
#include "rollsense/minirocket/minirocket.hpp"

namespace rollsense::minirocket {
namespace {

constexpr const char* kMagic = "rollsense-minirocket";
constexpr int kVersion = 2;
constexpr int kVersionWithoutRule = 1;  // still read: no series_rule line

using model_text::at_end;
using model_text::keyword;
using model_text::put_number;
using model_text::take;

}  // namespace

std::string Model::serialize(const Options& o) const {
    std::string out;
    out += std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
    out += "classes " + std::to_string(class_names.size()) + "\n";
    for (const auto& c : class_names) out += "class " + c + "\n";
    out += "channels " + std::to_string(channel_names.size()) + "\n";
    for (const auto& c : channel_names) out += "channel " + c + "\n";
    out += "series_length " + std::to_string(transform.length()) + "\n";
    out += "series_rule" + (series_rule.empty() ? "" : " " + series_rule) + "\n";
    const auto& t = transform.options();
    out += "options num_features=" + std::to_string(t.num_features) +
           " max_dilations_per_kernel=" + std::to_string(t.max_dilations_per_kernel) +
           " seed=" + std::to_string(t.seed) + " alpha_log10_low=";
    put_number(out, o.log10_alpha_low);
    out += " alpha_log10_high=";
    put_number(out, o.log10_alpha_high);
    out += " alphas=" + std::to_string(o.alphas) + "\n";
    out += "alpha ";
    put_number(out, alpha);
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
        put_number(out, transform.biases()[j]);
        out += ' ';
        put_number(out, mean[j]);
        out += ' ';
        put_number(out, scale[j]);
        for (std::size_t c = 0; c < k; ++c) {
            out += ' ';
            put_number(out, weights[j * k + c]);
        }
        out += '\n';
    }
    out += "intercept";
    for (double v : intercept) {
        out += ' ';
        put_number(out, v);
    }
    out += "\n";
    model_text::put_checksum(out);
    return out;
}

Status Model::deserialize(std::string_view text, const std::string& source, Options& options) {
    model_text::Reader in(text, source);
    std::string_view line, rest;
    if (!in.next(line) || !keyword(line, kMagic, rest))
        return Error{ErrorCode::parse_error, "'" + source + "' is not a rollsense MiniRocket model (it should start with '" +
                                                 kMagic + " " + std::to_string(kVersion) +
                                                 "'); is it another classifier's model? load it with that classifier"};
    int version = 0;
    if (!take(rest, version) || !at_end(rest)) return in.fail("malformed format version");
    if (version > kVersion)
        return in.fail("model format version " + std::to_string(version) + " is newer than this build reads (" +
                       std::to_string(kVersion) + "); update rollsense to read it");
    if (version != kVersion && version != kVersionWithoutRule)
        return in.fail("model format version " + std::to_string(version) + " is not supported");

    Model m;
    std::size_t k = 0, channels = 0, length = 0, combos = 0, p = 0;
    if (auto s = in.count("classes", 100000, k); !s) return s;
    if (k < 2) return in.fail("a model needs at least 2 classes");
    if (auto s = in.names("class", k, m.class_names); !s) return s;
    if (auto s = in.count("channels", 100000, channels); !s) return s;
    if (auto s = in.names("channel", channels, m.channel_names); !s) return s;
    if (auto s = in.count("series_length", 10000000, length); !s) return s;
    if (version != kVersionWithoutRule) {
        if (!in.next(line)) return in.truncated("reading the series rule");
        if (!keyword(line, "series_rule", rest)) return in.fail("expected the 'series_rule' line");
        m.series_rule = std::string(rest);
    }

    Options o = options;
    if (!in.next(line)) return in.truncated("reading the options");
    if (!keyword(line, "options", rest)) return in.fail("expected the 'options' line");
    // A word holds no spaces, so take() reading a number means it read all of it.
    auto option = [&](std::string_view key, std::string_view v) {
        if (key == "num_features") return take(v, o.transform.num_features);
        if (key == "max_dilations_per_kernel") return take(v, o.transform.max_dilations_per_kernel);
        if (key == "seed") return take(v, o.transform.seed);
        if (key == "alpha_log10_low") return take(v, o.log10_alpha_low);
        if (key == "alpha_log10_high") return take(v, o.log10_alpha_high);
        if (key == "alphas") return take(v, o.alphas);
        return true;  // unknown keys are informational: a newer writer may add some
    };
    if (auto s = in.options(rest, option); !s) return s;
    if (o.transform.num_features < kKernels || o.transform.num_features > 1000000 ||
        o.transform.max_dilations_per_kernel < 1 || o.transform.max_dilations_per_kernel > 1024)
        return in.fail("options out of range (num_features 84…1,000,000, max_dilations_per_kernel 1…1024)");

    if (!in.next(line)) return in.truncated("reading the chosen alpha");
    if (!keyword(line, "alpha", rest) || !take(rest, m.alpha) || !at_end(rest) || !(m.alpha > 0.0))
        return in.fail("expected 'alpha <positive number>'");

    if (auto s = m.transform.plan(channels, length, o.transform); !s) return in.fail(s.error().message);
    if (auto s = in.count("combinations", 10000000, combos); !s) return s;
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
    if (auto s = in.count("features", 10000000, p); !s) return s;
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

    if (auto s = in.checksum("the intercepts"); !s) return s;
    *this = std::move(m);
    options.transform = o.transform;
    options.log10_alpha_low = o.log10_alpha_low;
    options.log10_alpha_high = o.log10_alpha_high;
    options.alphas = o.alphas;
    return {};
}

}  // namespace rollsense::minirocket
