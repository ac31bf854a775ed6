// Issue 22 item 6: a model file declaring huge counts made the loaders of
// every classifier plugin (bagged_trees, nearest_centroid, minirocket)
// allocate gigabytes (std::length_error / bad_alloc escaped the Status API).
// Each case runs in a child capped at 2 GiB of address space.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "address_space_limit.hpp"
#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "rollsense/minirocket/minirocket.hpp"
#include "rollsense/minirocket/transform.hpp"
#include "rollsense/nearest_centroid/nearest_centroid.hpp"

using namespace rollsense;
using rollsense::testing::ChildOutcome;
using rollsense::testing::run_with_address_space_limit;

namespace {

constexpr std::size_t kTwoGiB = std::size_t{2} << 30;

// FNV-1a 64, the model files' checksum, so the damaged files below are
// refused for their counts and not merely for a wrong checksum.
std::string with_checksum(std::string body) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : body) h = (h ^ c) * 0x100000001b3ULL;
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return body + "checksum " + buf + "\n";
}

std::string bagged_trees_header(std::size_t trees) {
    return "rollsense-bagged-trees 1\nclasses 2\nclass a\nclass b\nfeatures 1\nfeature f\n"
           "options learners=1 min_leaf_size=1 min_parent_size=2 max_num_splits=0 predictors_per_split=0 "
           "criterion=gdi seed=1\ntrees " + std::to_string(trees) + "\n";
}

// Load `text` through the plugin's file loader in a capped child: passes when
// the load fails with a message naming the line and containing `expect`.
template <class Classifier>
ChildOutcome load_refused(const std::string& text, const std::string& expect) {
    const auto file = std::filesystem::temp_directory_path() /
                      ("rollsense-test-bounds-" + std::to_string(::getpid()) + ".rsm");
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out << text;
    }
    const auto outcome = run_with_address_space_limit(kTwoGiB, [&] {
        Classifier c;
        const auto s = c.load(file);
        return !s.ok() && s.message().find(expect) != std::string::npos &&
               s.message().find(file.string()) != std::string::npos;
    });
    std::filesystem::remove(file);
    return outcome;
}

}  // namespace

TEST_CASE("a bagged-trees model declaring a huge node count is refused before allocating",
          "[bagged_trees][model][bounds]") {
    // 2e9 nodes: ~15.6 GB of vectors on main.
    const auto text = with_checksum(bagged_trees_header(1) + "tree 0 2000000000 1\n-1 0 0\n0.5 0.5\n");
    CHECK(load_refused<bagged_trees::BaggedTrees>(text, "line 9: tree declares 2000000000 nodes") ==
          ChildOutcome::passed);
}

TEST_CASE("a bagged-trees model declaring a huge leaf count is refused before allocating",
          "[bagged_trees][model][bounds]") {
    const auto text = with_checksum(bagged_trees_header(1) + "tree 0 4000000000 3999999999\n-1 0 0\n");
    CHECK(load_refused<bagged_trees::BaggedTrees>(text, "bytes follow") == ChildOutcome::passed);
}

TEST_CASE("a bagged-trees model declaring a million trees it does not hold is refused",
          "[bagged_trees][model][bounds]") {
    const auto text = with_checksum(bagged_trees_header(1000000) + "tree 0 1 1\n-1 0 0\n0.5 0.5\n");
    CHECK(load_refused<bagged_trees::BaggedTrees>(text, "line 8: declares 1000000 trees") == ChildOutcome::passed);
}

TEST_CASE("a nearest-centroid model declaring K x P beyond its size is refused before allocating",
          "[nearest_centroid][model][bounds]") {
    // 100000 classes x 1000000 features: 800 GB of centroids on main; the
    // names themselves take ~16 MB of file.
    std::string text = "rollsense-nearest-centroid 1\noptions shrink=0 temperature=1\nclasses 100000\n";
    for (int c = 0; c < 100000; ++c) text += "class 1 c" + std::to_string(c) + "\n";
    text += "features 1000000\n";
    for (int j = 0; j < 1000000; ++j) text += "feature 0 1 f\n";
    text += "centroid 0 0\n";
    CHECK(load_refused<nearest_centroid::NearestCentroid>(with_checksum(text), "bytes follow") ==
          ChildOutcome::passed);
}

TEST_CASE("a file far larger than any model is refused by its size", "[bagged_trees][model][bounds]") {
    const auto file = std::filesystem::temp_directory_path() /
                      ("rollsense-test-big-" + std::to_string(::getpid()) + ".rsm");
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out << "rollsense-bagged-trees 1\n";
    }
    std::filesystem::resize_file(file, (std::uintmax_t{1} << 30) + 1);  // sparse: takes no disk
    const auto outcome = run_with_address_space_limit(kTwoGiB, [&] {
        bagged_trees::BaggedTrees a;
        nearest_centroid::NearestCentroid b;
        const auto sa = a.load(file), sb = b.load(file);
        return !sa.ok() && !sb.ok() && sa.message().find("MiB") != std::string::npos &&
               sb.message().find("MiB") != std::string::npos;
    });
    std::filesystem::remove(file);
    CHECK(outcome == ChildOutcome::passed);
}

TEST_CASE("a MiniRocket model declaring P x K weights beyond its size is refused before allocating",
          "[minirocket][model][bounds]") {
    // 100000 classes and the stock transform's ~10000 features: 4 GB of
    // weights on main; the class names take ~1 MB of file.
    minirocket::TransformOptions opts;
    minirocket::Transform plan;
    REQUIRE(plan.plan(1, 128, opts).ok());
    std::string text = "rollsense-minirocket 1\nclasses 100000\n";
    for (int c = 0; c < 100000; ++c) text += "class c" + std::to_string(c) + "\n";
    text += "channels 1\nchannel ch1\nseries_length 128\noptions num_features=" + std::to_string(opts.num_features) +
            " max_dilations_per_kernel=" + std::to_string(opts.max_dilations_per_kernel) +
            " seed=1 alpha_log10_low=-3 alpha_log10_high=3 alphas=10\nalpha 1\ncombinations " +
            std::to_string(plan.combinations().size()) + "\n";
    for (std::size_t i = 0; i < plan.combinations().size(); ++i) text += "0\n";
    text += "features " + std::to_string(plan.features()) + "\n0 0 1 0\n";
    CHECK(load_refused<minirocket::MiniRocket>(with_checksum(text), "weights each but only") ==
          ChildOutcome::passed);
}

TEST_CASE("a MiniRocket model declaring more combinations than it holds is refused",
          "[minirocket][model][bounds]") {
    std::string text = "rollsense-minirocket 1\nclasses 2\nclass a\nclass b\nchannels 1\nchannel ch1\n"
                       "series_length 10000000\noptions num_features=1000000 max_dilations_per_kernel=1024 seed=1\n"
                       "alpha 1\n";
    minirocket::TransformOptions opts;
    opts.num_features = 1000000;
    opts.max_dilations_per_kernel = 1024;
    minirocket::Transform plan;
    REQUIRE(plan.plan(1, 10000000, opts).ok());
    text += "combinations " + std::to_string(plan.combinations().size()) + "\n0\n";
    CHECK(load_refused<minirocket::MiniRocket>(with_checksum(text), "combinations but only") ==
          ChildOutcome::passed);
}
