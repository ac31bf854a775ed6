// The transform against values worked out by hand and a naive convolution.
#include <catch2/catch.hpp>

#include <numeric>
#include <set>

#include "rollsense/minirocket/transform.hpp"
#include "shapes.hpp"

using namespace rollsense::minirocket;

namespace {
// Σ_j w_j x[t + (j − 4) d], zero outside the series: the definition, in double.
std::vector<double> naive(const std::vector<float>& x, int kernel, int d) {
    const auto twos = kernel_twos(kernel);
    std::vector<double> out(x.size(), 0.0);
    const int L = static_cast<int>(x.size());
    for (int t = 0; t < L; ++t)
        for (int j = 0; j < 9; ++j) {
            const int s = t + (j - 4) * d;
            if (s < 0 || s >= L) continue;
            const double w = (j == twos[0] || j == twos[1] || j == twos[2]) ? 2.0 : -1.0;
            out[static_cast<std::size_t>(t)] += w * x[static_cast<std::size_t>(s)];
        }
    return out;
}

std::vector<float> ramp(std::size_t n) {
    std::vector<float> x(n);
    std::iota(x.begin(), x.end(), 0.0f);
    return x;
}
}  // namespace

TEST_CASE("the 84 kernels are the distinct placements of three +2 weights", "[minirocket][transform]") {
    std::set<std::array<int, 3>> seen;
    for (int k = 0; k < kKernels; ++k) seen.insert(kernel_twos(k));
    CHECK(seen.size() == 84);
    CHECK(kernel_twos(0) == std::array<int, 3>{0, 1, 2});
    CHECK(kernel_twos(1) == std::array<int, 3>{0, 1, 3});
    CHECK(kernel_twos(83) == std::array<int, 3>{6, 7, 8});
    CHECK_THROWS(kernel_twos(84));
}

TEST_CASE("the layout spreads dilations exponentially and spends ~10,000 features", "[minirocket][transform]") {
    Transform t;
    REQUIRE(t.plan(3, 128, {}).ok());
    CHECK(t.features() == 9996);  // 119 per kernel
    const auto& d = t.dilations();
    REQUIRE(!d.empty());
    CHECK(d.front() == 1);
    CHECK(d.back() == 15);  // floor((128 − 1) / 8)
    CHECK(std::is_sorted(d.begin(), d.end()));
    CHECK(std::adjacent_find(d.begin(), d.end()) == d.end());
    const auto& f = t.features_per_dilation();
    CHECK(std::accumulate(f.begin(), f.end(), 0) == 119);
    // Small dilations repeat in the exponential spread, so they keep more features.
    CHECK(f.front() > f.back());
    REQUIRE(t.combinations().size() == d.size() * 84);
    for (const auto& c : t.combinations()) {
        CHECK(!c.channels.empty());
        CHECK(c.channels.size() <= 3);
        CHECK(c.padded == ((c.dilation_index + c.kernel) % 2 == 0));
    }

    CHECK(!t.plan(1, 8, {}).ok());  // shorter than a kernel
    CHECK(!t.plan(0, 128, {}).ok());
    TransformOptions few;
    few.num_features = 83;
    CHECK(!t.plan(1, 128, few).ok());
    Transform nine;
    REQUIRE(nine.plan(1, 9, {}).ok());
    CHECK(nine.dilations() == std::vector<int>{1});
}

TEST_CASE("convolution with a length-9 kernel at dilations 1 and 2 matches hand values", "[minirocket][transform]") {
    Transform t;
    REQUIRE(t.plan(1, 20, {}).ok());  // (20 − 1) / 8 ≥ 2: dilations 1 and 2
    REQUIRE(t.dilations() == std::vector<int>{1, 2});
    const auto x = ramp(20);  // x[t] = t
    std::vector<float> out(20);

    const auto& k0d1 = t.combinations()[0];  // kernel 0 (+2 at 0, 1, 2), dilation 1
    REQUIRE(k0d1.kernel == 0);
    t.convolve(x, k0d1, out);
    CHECK(out[0] == -10.0f);  // −(0 + 1 + 2 + 3 + 4): only the −1 taps see the series
    CHECK(out[4] == -27.0f);  // 2·(0 + 1 + 2) − (3 + … + 8)
    CHECK(out[10] == -27.0f);
    const auto ref1 = naive(x, 0, 1);
    for (std::size_t i = 0; i < 20; ++i) CHECK(out[i] == Approx(ref1[i]));

    const auto& k0d2 = t.combinations()[84];  // kernel 0, dilation 2
    REQUIRE(k0d2.dilation_index == 1);
    t.convolve(x, k0d2, out);
    CHECK(out[8] == -54.0f);  // 2·(0 + 2 + 4) − (6 + 8 + … + 16)
    const auto ref2 = naive(x, 0, 2);
    for (std::size_t i = 0; i < 20; ++i) CHECK(out[i] == Approx(ref2[i]));

    // Any kernel on a constant series sums to zero inside (the weights sum to 0).
    std::vector<float> flat(20, 5.0f);
    t.convolve(flat, t.combinations()[37], out);
    CHECK(out[10] == 0.0f);
}

TEST_CASE("PPV counts outputs above the bias over the padded or the valid range", "[minirocket][transform]") {
    Transform t;
    REQUIRE(t.plan(1, 20, {}).ok());
    const auto x = ramp(20);
    const auto& combos = t.combinations();
    const auto& k1 = combos[1];  // kernel 1 (+2 at 0, 1, 3), dilation 1: unpadded
    REQUIRE(!k1.padded);
    REQUIRE(combos[0].padded);

    // Inside, kernel 1 on a ramp is 2·(−4 − 3 − 1) − (−2 + 0 + 1 + 2 + 3 + 4) = −24 everywhere.
    std::vector<float> biases(t.features(), 0.0f);
    for (int f = 0; f < k1.features; ++f) biases[static_cast<std::size_t>(k1.first_feature + f)] = f % 2 ? -24.5f : -24.0f;
    // Kernel 0 padded: outputs from the naive convolution, bias −20.
    for (int f = 0; f < combos[0].features; ++f) biases[static_cast<std::size_t>(combos[0].first_feature + f)] = -20.0f;
    std::vector<std::vector<int>> subsets(combos.size(), std::vector<int>{0});
    REQUIRE(t.restore(subsets, biases).ok());

    std::vector<float> feats(t.features());
    t.transform_one(x, feats);
    CHECK(feats[static_cast<std::size_t>(k1.first_feature)] == 0.0f);      // −24 > −24 nowhere
    CHECK(feats[static_cast<std::size_t>(k1.first_feature + 1)] == 1.0f);  // −24 > −24.5 on all 12 valid outputs

    const auto ref = naive(x, 0, 1);
    const double above = static_cast<double>(std::count_if(ref.begin(), ref.end(), [](double v) { return v > -20.0; }));
    CHECK(feats[static_cast<std::size_t>(combos[0].first_feature)] == Approx(above / 20.0));
    CHECK(above > 0.0);
    CHECK(above < 20.0);  // the zero-padded edges fall below −20: the bias does separate
}

TEST_CASE("a combination sums its convolution over its channels", "[minirocket][transform]") {
    Transform t;
    REQUIRE(t.plan(2, 20, {}).ok());
    std::vector<float> two(40);
    for (std::size_t i = 0; i < 20; ++i) {
        two[i] = static_cast<float>(i);
        two[20 + i] = static_cast<float>(i * i % 7);
    }
    Combination c = t.combinations()[5];
    std::vector<float> a(20), b(20), both(20);
    c.channels = {0};
    t.convolve(two, c, a);
    c.channels = {1};
    t.convolve(two, c, b);
    c.channels = {0, 1};
    t.convolve(two, c, both);
    for (std::size_t i = 0; i < 20; ++i) CHECK(both[i] == Approx(a[i] + b[i]));
}

TEST_CASE("biases are low-discrepancy quantiles of a training series' convolution", "[minirocket][transform]") {
    CHECK(feature_quantile(0) == Approx(0.6180339887));
    CHECK(feature_quantile(1) == Approx(0.2360679775));
    const std::vector<float> sorted{1.0f, 2.0f, 4.0f};
    CHECK(linear_quantile(sorted, 0.0) == 1.0f);
    CHECK(linear_quantile(sorted, 0.75) == 3.0f);
    CHECK(linear_quantile(sorted, 1.0) == 4.0f);

    const auto x = ramp(20);
    Transform t;
    REQUIRE(t.fit(x, 1, 1, 20, {}).ok());  // one training series: every bias comes from it
    std::vector<float> conv(20);
    const auto& c = t.combinations()[7];
    t.convolve(x, c, conv);
    std::sort(conv.begin(), conv.end());
    for (int f = 0; f < c.features; ++f) {
        const auto i = static_cast<std::size_t>(c.first_feature + f);
        CHECK(t.biases()[i] == linear_quantile(conv, feature_quantile(i)));
    }
}

TEST_CASE("the transform is deterministic for a seed and independent of threads", "[minirocket][transform]") {
    const auto data = shapes::make(10, 64, 3);
    std::vector<float> x(data.x.begin(), data.x.end());
    TransformOptions o;
    o.seed = 42;
    Transform a, b, c;
    REQUIRE(a.fit(x, data.rows, 3, 64, o).ok());
    REQUIRE(b.fit(x, data.rows, 3, 64, o).ok());
    o.seed = 43;
    REQUIRE(c.fit(x, data.rows, 3, 64, o).ok());
    CHECK(a.biases() == b.biases());
    CHECK(a.biases() != c.biases());
    bool subsets_differ = false;
    for (std::size_t i = 0; i < a.combinations().size(); ++i) {
        CHECK(a.combinations()[i].channels == b.combinations()[i].channels);
        subsets_differ |= a.combinations()[i].channels != c.combinations()[i].channels;
    }
    CHECK(subsets_differ);

    std::vector<float> one(data.rows * a.features()), two(one.size());
    a.transform(x, data.rows, one, 1);
    a.transform(x, data.rows, two, 2);
    CHECK(one == two);
    CHECK(!a.fit(std::span<const float>(x).first(10), data.rows, 3, 64, o).ok());  // wrong size
}
