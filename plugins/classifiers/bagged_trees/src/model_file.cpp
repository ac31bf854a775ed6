// The bagged-trees model file: versioned, line-oriented text so a model can be
// inspected, diffed and loaded anywhere; numbers are written in the shortest
// form that reads back as the same double, so a reloaded model predicts
// exactly what the saved one did. A checksum line at the end catches both
// truncation and damage.
//
//   rollsense-bagged-trees 1
//   classes K            then K lines "class <name>"
//   features P           then P lines "feature <name>"
//   options learners=30 min_leaf_size=1 min_parent_size=2 max_num_splits=0 predictors_per_split=0 criterion=gdi seed=1
//   trees B
//   tree <b> <nodes> <leaves>, then <nodes> lines "<feature> <threshold> <child>"
//                              and <leaves> lines of K class probabilities
//   checksum <FNV-1a 64 of every byte before this line, 16 hex digits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <sstream>  // load(): the file into memory

#include "rollsense/model_text.hpp"
#include "rollsense/atomic_file.hpp"
#include "rollsense/bagged_trees/ensemble.hpp"

namespace rollsense::bagged_trees {
namespace {

constexpr const char* kMagic = "rollsense-bagged-trees";
constexpr int kVersion = 1;
// Smallest a node line ("0 0 0\n") and a tree ("tree 0 1 1\n", one node line,
// one leaf line) can be: the bounds declared counts are checked against.
constexpr std::size_t kMinNodeBytes = 6;
constexpr std::size_t kMinTreeBytes = 11 + kMinNodeBytes + 2;
// Far above any model rollsense trains (the stock model is ~100 kB), far below
// what would exhaust a machine reading it.
constexpr std::uintmax_t kMaxModelBytes = std::uintmax_t{1} << 30;

using model_text::at_end;
using model_text::keyword;
using model_text::put_number;
using model_text::take;

}  // namespace

std::string Ensemble::serialize() const {
    std::string out;
    out += std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
    out += "classes " + std::to_string(class_names_.size()) + "\n";
    for (const auto& c : class_names_) out += "class " + c + "\n";
    out += "features " + std::to_string(feature_names_.size()) + "\n";
    for (const auto& f : feature_names_) out += "feature " + f + "\n";
    const auto& o = options_;
    out += "options learners=" + std::to_string(o.learners) + " min_leaf_size=" +
           std::to_string(o.tree.min_leaf_size) + " min_parent_size=" + std::to_string(o.tree.min_parent_size) +
           " max_num_splits=" + std::to_string(o.tree.max_num_splits) +
           " predictors_per_split=" + std::to_string(o.tree.predictors_per_split) +
           " criterion=" + std::string(to_string(o.tree.criterion)) + " seed=" + std::to_string(o.seed) + "\n";
    out += "trees " + std::to_string(trees_.size()) + "\n";
    const std::size_t k = classes();
    for (std::size_t b = 0; b < trees_.size(); ++b) {
        const Tree& t = trees_[b];
        const std::size_t leaves = t.leaf_probs.size() / std::max<std::size_t>(k, 1);
        out += "tree " + std::to_string(b) + " " + std::to_string(t.nodes()) + " " + std::to_string(leaves) + "\n";
        for (std::size_t i = 0; i < t.nodes(); ++i) {
            out += std::to_string(t.feature[i]);
            out += ' ';
            put_number(out, t.threshold[i]);
            out += ' ';
            out += std::to_string(t.child[i]);
            out += '\n';
        }
        for (std::size_t l = 0; l < leaves; ++l) {
            for (std::size_t c = 0; c < k; ++c) {
                if (c) out += ' ';
                put_number(out, t.leaf_probs[l * k + c]);
            }
            out += '\n';
        }
    }
    model_text::put_checksum(out);
    return out;
}

Status Ensemble::deserialize(std::string_view text, const std::string& source) {
    model_text::Reader in(text, source);
    std::string_view line, rest;
    if (!in.next(line) || !keyword(line, kMagic, rest))
        return Error{ErrorCode::parse_error, "'" + source +
                                                 "' is not a rollsense bagged-trees model (it should start with '" +
                                                 kMagic + " " + std::to_string(kVersion) + "')"};
    int version = 0;
    if (!take(rest, version) || !at_end(rest)) return in.fail("malformed format version");
    if (version != kVersion)
        return in.fail("model format version " + std::to_string(version) + " is not supported by this build (it reads version " +
                       std::to_string(kVersion) + ")");

    std::size_t k = 0, p = 0, b = 0;
    std::vector<std::string> classes, features;
    if (auto s = in.count("classes", 100000, k); !s) return s;
    if (auto s = in.names("class", k, classes); !s) return s;
    if (auto s = in.count("features", 1000000, p); !s) return s;
    if (auto s = in.names("feature", p, features); !s) return s;

    EnsembleOptions opts;
    if (!in.next(line)) return in.truncated("reading the options");
    if (!keyword(line, "options", rest)) return in.fail("expected the 'options' line");
    // A word holds no spaces, so take() reading a number means it read all of it.
    auto option = [&](std::string_view key, std::string_view value) {
        if (key == "learners") return take(value, opts.learners);
        if (key == "min_leaf_size") return take(value, opts.tree.min_leaf_size);
        if (key == "min_parent_size") return take(value, opts.tree.min_parent_size);
        if (key == "max_num_splits") return take(value, opts.tree.max_num_splits);
        if (key == "predictors_per_split") return take(value, opts.tree.predictors_per_split);
        if (key == "seed") return take(value, opts.seed);
        if (key == "criterion") {
            auto c = parse_split_criterion(value);
            if (c) opts.tree.criterion = *c;
            return static_cast<bool>(c);
        }
        return true;  // unknown keys are informational: a newer writer may add some
    };
    if (auto s = in.options(rest, option); !s) return s;
    if (auto s = in.count("trees", 1000000, b); !s) return s;

    // Every tree takes at least a header line and two node lines ("0 0 0\n"
    // is 6 bytes), so a count the rest of the file cannot hold is refused
    // before anything is allocated for it.
    if (b > in.remaining() / kMinTreeBytes)
        return in.fail("declares " + std::to_string(b) + " trees but only " + std::to_string(in.remaining()) +
                       " bytes follow");
    std::vector<Tree> trees(b);
    for (std::size_t ti = 0; ti < b; ++ti) {
        const std::string doing = "reading tree " + std::to_string(ti + 1) + " of " + std::to_string(b);
        if (!in.next(line)) return in.truncated(doing);
        std::size_t index = 0, nodes = 0, leaves = 0;
        if (!keyword(line, "tree", rest) || !take(rest, index) || !take(rest, nodes) ||
            !take(rest, leaves) || !at_end(rest))
            return in.fail("expected 'tree <index> <nodes> <leaves>'");
        if (index != ti) return in.fail("tree " + std::to_string(index) + " where tree " + std::to_string(ti) + " belongs");
        if (nodes == 0 || leaves == 0 || leaves > nodes) return in.fail("tree with " + std::to_string(nodes) +
                                                                        " nodes and " + std::to_string(leaves) + " leaves");
        // A node line is at least "0 0 0\n" (6 bytes) and a leaf line at least
        // K numbers of 2 bytes ("0 " or "0\n"): what the rest of the file
        // cannot hold is refused before the vectors are sized for it.
        if (nodes > in.remaining() / kMinNodeBytes || leaves > in.remaining() / (2 * k) ||
            nodes * kMinNodeBytes + leaves * 2 * k > in.remaining())
            return in.fail("tree declares " + std::to_string(nodes) + " nodes and " + std::to_string(leaves) +
                           " leaves but only " + std::to_string(in.remaining()) + " bytes follow");
        Tree& t = trees[ti];
        t.feature.resize(nodes);
        t.threshold.resize(nodes);
        t.child.resize(nodes);
        std::size_t leaf_seen = 0;
        for (std::size_t i = 0; i < nodes; ++i) {
            if (!in.next(line)) return in.truncated(doing);
            rest = line;
            if (!take(rest, t.feature[i]) || !take(rest, t.threshold[i]) ||
                !take(rest, t.child[i]) || !at_end(rest))
                return in.fail("expected '<feature> <threshold> <child>'");
            // Structure checks: children come after their parent (no loops),
            // features and leaves in range, so a damaged file cannot crash predict().
            if (t.feature[i] >= 0) {
                if (static_cast<std::size_t>(t.feature[i]) >= p) return in.fail("feature index out of range");
                if (t.child[i] <= static_cast<std::int32_t>(i) || static_cast<std::size_t>(t.child[i]) + 1 >= nodes)
                    return in.fail("child index out of range");
                if (!std::isfinite(t.threshold[i])) return in.fail("threshold is not finite");
            } else {
                if (t.feature[i] != -1 || t.child[i] < 0 || static_cast<std::size_t>(t.child[i]) >= leaves)
                    return in.fail("leaf index out of range");
                ++leaf_seen;
            }
        }
        if (leaf_seen != leaves) return in.fail("tree declares " + std::to_string(leaves) + " leaves but has " +
                                                std::to_string(leaf_seen));
        t.leaf_probs.resize(leaves * k);
        for (std::size_t l = 0; l < leaves; ++l) {
            if (!in.next(line)) return in.truncated(doing);
            rest = line;
            for (std::size_t c = 0; c < k; ++c) {
                double& v = t.leaf_probs[l * k + c];
                if (!take(rest, v) || !std::isfinite(v) || v < 0.0 || v > 1.0)
                    return in.fail("expected " + std::to_string(k) + " class probabilities in [0, 1]");
            }
            if (!at_end(rest)) return in.fail("more than " + std::to_string(k) + " class probabilities");
        }
    }
    if (auto s = in.checksum("the last tree"); !s) return s;

    class_names_ = std::move(classes);
    feature_names_ = std::move(features);
    trees_ = std::move(trees);
    options_ = opts;
    return {};
}

Status Ensemble::save(const std::filesystem::path& file) const {
    if (!trained()) return {ErrorCode::state_error, "bagged_trees: nothing to save to '" + file.string() +
                                                        "': the model is not trained"};
    for (const auto* names : {&class_names_, &feature_names_})
        for (const auto& n : *names)
            if (n.find('\n') != std::string::npos || n.find('\r') != std::string::npos)
                return {ErrorCode::invalid_argument, "bagged_trees: name '" + n + "' contains a line break"};
    return write_file_atomic(file, serialize());
}

Status Ensemble::load(const std::filesystem::path& file) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    if (!ec && size > kMaxModelBytes)
        return {ErrorCode::parse_error, "model file '" + file.string() + "' is " + std::to_string(size >> 20) +
                                            " MiB, more than any bagged-trees model (limit " +
                                            std::to_string(kMaxModelBytes >> 20) +
                                            " MiB): not a model file? retrain with 'rollsense train'"};
    std::ifstream in(file, std::ios::binary);
    if (!in)
        return {ErrorCode::not_found, "model file '" + file.string() + "' cannot be opened (does it exist? train one "
                                                                         "with 'rollsense train DATASET -o MODEL')"};
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) return {ErrorCode::io_error, "model file '" + file.string() + "' could not be read"};
    // deserialize() checks every count before allocating; this only keeps a
    // machine out of memory from escaping the Status API as an exception.
    try {
        return deserialize(ss.str(), file.string());
    } catch (const std::exception& e) {
        return {ErrorCode::io_error, "model file '" + file.string() + "' could not be loaded: " + e.what()};
    }
}

}  // namespace rollsense::bagged_trees
