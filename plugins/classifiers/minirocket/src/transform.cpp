#include "rollsense/minirocket/transform.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "rollsense/minirocket/parallel.hpp"
#include "rollsense/random.hpp"

namespace rollsense::minirocket {

std::array<int, 3> kernel_twos(int kernel) {
    static const std::vector<std::array<int, 3>> table = [] {
        std::vector<std::array<int, 3>> t;
        for (int a = 0; a < kKernelLength; ++a)
            for (int b = a + 1; b < kKernelLength; ++b)
                for (int c = b + 1; c < kKernelLength; ++c) t.push_back({a, b, c});
        return t;
    }();
    return table.at(static_cast<std::size_t>(kernel));
}

double feature_quantile(std::size_t i) {
    const double phi = (std::sqrt(5.0) + 1.0) / 2.0;
    const double v = static_cast<double>(i + 1) * phi;
    return v - std::floor(v);
}

float linear_quantile(std::span<const float> values, double q) {
    const double pos = q * static_cast<double>(values.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    const double frac = pos - static_cast<double>(lo);
    return static_cast<float>(values[lo] + frac * (static_cast<double>(values[hi]) - values[lo]));
}

// Per dilation and channel: A = the sum of the nine shifted copies of −X
// (every weight at −1), and G_j = the copy shifted for position j times 3.
// Kernel k's convolution is then A + G_a + G_b + G_c (its +2 positions: −1 + 3),
// additions only, shared by all 84 kernels of the dilation.
struct Transform::Scratch {
    std::vector<float> alpha;  // channels × L
    std::vector<float> gamma;  // channels × 9 × L
    std::vector<float> conv;   // L
};

Status Transform::plan(std::size_t channels, std::size_t length, const TransformOptions& o) {
    if (channels == 0)
        return Error{ErrorCode::invalid_argument, "minirocket: the series have no channels"};
    if (length < static_cast<std::size_t>(kKernelLength))
        return Error{ErrorCode::invalid_argument,
                     "minirocket: series of " + std::to_string(length) + " samples are shorter than one kernel (" +
                         std::to_string(kKernelLength) + "); prepare longer series"};
    if (o.num_features < kKernels)
        return Error{ErrorCode::invalid_argument, "minirocket: num_features " + std::to_string(o.num_features) +
                                                      " is below one feature per kernel (84)"};
    if (o.max_dilations_per_kernel < 1)
        return Error{ErrorCode::invalid_argument, "minirocket: max_dilations_per_kernel must be at least 1"};
    options_ = o;
    channels_ = channels;
    length_ = length;

    // Dilations 2^e for e evenly spaced in [0, log2((L − 1) / 8)], floored and
    // de-duplicated; each keeps as many features as copies it had, scaled to
    // the per-kernel budget, the rounding remainder handed out from the smallest.
    const int per_kernel = o.num_features / kKernels;
    const int count = std::min(per_kernel, o.max_dilations_per_kernel);
    const double multiplier = static_cast<double>(per_kernel) / count;
    const double max_exponent = std::log2(static_cast<double>(length - 1) / (kKernelLength - 1));
    dilations_.clear();
    std::vector<int> copies;
    for (int i = 0; i < count; ++i) {
        const double e = count == 1 ? 0.0 : max_exponent * i / (count - 1);
        const int d = static_cast<int>(std::floor(std::pow(2.0, e)));
        if (!dilations_.empty() && dilations_.back() == d) {
            ++copies.back();
        } else {
            dilations_.push_back(d);
            copies.push_back(1);
        }
    }
    features_per_dilation_.assign(dilations_.size(), 0);
    int assigned = 0;
    for (std::size_t i = 0; i < copies.size(); ++i) {
        features_per_dilation_[i] = static_cast<int>(std::floor(copies[i] * multiplier));
        assigned += features_per_dilation_[i];
    }
    for (std::size_t i = 0; assigned < per_kernel; i = (i + 1) % copies.size(), ++assigned)
        ++features_per_dilation_[i];

    // Channel subsets: a count drawn log-uniformly in [1, min(channels, 9)],
    // then that many distinct channels.
    auto rng = random::Xoshiro256ss::named_stream(o.seed, "minirocket-channels");
    const int max_channels = static_cast<int>(std::min<std::size_t>(channels, kKernelLength));
    const double channel_exponent = std::log2(max_channels + 1.0);
    combinations_.clear();
    int feature = 0;
    for (std::size_t di = 0; di < dilations_.size(); ++di) {
        for (int k = 0; k < kKernels; ++k) {
            Combination c;
            c.dilation_index = static_cast<int>(di);
            c.kernel = k;
            c.padded = (static_cast<int>(di) + k) % 2 == 0;  // alternate, as the paper
            c.first_feature = feature;
            c.features = features_per_dilation_[di];
            feature += c.features;
            const int n = std::clamp(static_cast<int>(std::pow(2.0, rng.uniform(0.0, channel_exponent))), 1,
                                     max_channels);
            std::vector<int> all(channels);
            std::iota(all.begin(), all.end(), 0);
            for (int j = 0; j < n; ++j)
                std::swap(all[static_cast<std::size_t>(j)],
                          all[static_cast<std::size_t>(j) + rng.below(channels - static_cast<std::size_t>(j))]);
            c.channels.assign(all.begin(), all.begin() + n);
            std::sort(c.channels.begin(), c.channels.end());
            combinations_.push_back(std::move(c));
        }
    }
    biases_.assign(static_cast<std::size_t>(feature), 0.0f);
    return {};
}

Status Transform::fit(std::span<const float> series, std::size_t rows, std::size_t channels, std::size_t length,
                      const TransformOptions& o) {
    if (rows == 0) return Error{ErrorCode::invalid_argument, "minirocket: no training series"};
    if (series.size() != rows * channels * length)
        return Error{ErrorCode::invalid_argument, "minirocket: " + std::to_string(series.size()) +
                                                      " samples for " + std::to_string(rows) + " series of " +
                                                      std::to_string(channels) + " × " + std::to_string(length)};
    if (auto s = plan(channels, length, o); !s) return s;
    // One random training series per combination; its full-length convolution's
    // quantiles at the combination's slice of the low-discrepancy sequence.
    auto rng = random::Xoshiro256ss::named_stream(o.seed, "minirocket-biases");
    const std::size_t width = channels * length;
    Scratch s;
    std::vector<float> conv(length);
    for (const auto& c : combinations_) {
        const std::size_t r = rng.below(rows);
        const auto one = series.subspan(r * width, width);
        dilation_bases(one, dilations_[static_cast<std::size_t>(c.dilation_index)], s);
        combine(s, c, conv.data());
        std::sort(conv.begin(), conv.end());
        for (int f = 0; f < c.features; ++f) {
            const auto i = static_cast<std::size_t>(c.first_feature + f);
            biases_[i] = linear_quantile(conv, feature_quantile(i));
        }
    }
    return {};
}

Status Transform::restore(std::vector<std::vector<int>> subsets, std::vector<float> biases) {
    if (subsets.size() != combinations_.size() || biases.size() != biases_.size())
        return Error{ErrorCode::invalid_argument, "minirocket: saved transform has " + std::to_string(subsets.size()) +
                                                      " combinations and " + std::to_string(biases.size()) +
                                                      " biases, the layout has " +
                                                      std::to_string(combinations_.size()) + " and " +
                                                      std::to_string(biases_.size())};
    for (std::size_t i = 0; i < subsets.size(); ++i) {
        auto& ch = subsets[i];
        if (ch.empty() || ch.size() > channels_ || !std::is_sorted(ch.begin(), ch.end()) ||
            std::adjacent_find(ch.begin(), ch.end()) != ch.end() || ch.front() < 0 ||
            static_cast<std::size_t>(ch.back()) >= channels_)
            return Error{ErrorCode::invalid_argument,
                         "minirocket: combination " + std::to_string(i) + " has an invalid channel subset"};
        combinations_[i].channels = std::move(ch);
    }
    biases_ = std::move(biases);
    return {};
}

void Transform::dilation_bases(std::span<const float> series, int dilation, Scratch& s) const {
    const auto L = static_cast<std::ptrdiff_t>(length_);
    s.alpha.assign(channels_ * length_, 0.0f);
    s.gamma.assign(channels_ * kKernelLength * length_, 0.0f);
    for (std::size_t ch = 0; ch < channels_; ++ch) {
        const float* x = series.data() + ch * length_;
        float* a = s.alpha.data() + ch * length_;
        for (int j = 0; j < kKernelLength; ++j) {
            // Output t sees input t + shift; outside the series counts as zero.
            const std::ptrdiff_t shift = static_cast<std::ptrdiff_t>(j - kKernelLength / 2) * dilation;
            const std::ptrdiff_t begin = std::max<std::ptrdiff_t>(0, -shift);
            const std::ptrdiff_t end = std::min<std::ptrdiff_t>(L, L - shift);
            float* g = s.gamma.data() + (ch * kKernelLength + static_cast<std::size_t>(j)) * length_;
            for (std::ptrdiff_t t = begin; t < end; ++t) {
                a[t] -= x[t + shift];
                g[t] = 3.0f * x[t + shift];
            }
        }
    }
}

void Transform::combine(const Scratch& s, const Combination& c, float* out) const {
    const std::size_t L = length_;
    const auto twos = kernel_twos(c.kernel);
    std::fill(out, out + L, 0.0f);
    for (int ch : c.channels) {
        const auto chs = static_cast<std::size_t>(ch);
        const float* a = s.alpha.data() + chs * L;
        const float* g0 = s.gamma.data() + (chs * kKernelLength + static_cast<std::size_t>(twos[0])) * L;
        const float* g1 = s.gamma.data() + (chs * kKernelLength + static_cast<std::size_t>(twos[1])) * L;
        const float* g2 = s.gamma.data() + (chs * kKernelLength + static_cast<std::size_t>(twos[2])) * L;
        for (std::size_t t = 0; t < L; ++t) out[t] += a[t] + g0[t] + g1[t] + g2[t];
    }
}

void Transform::convolve(std::span<const float> series, const Combination& c, std::span<float> out) const {
    Scratch s;
    dilation_bases(series, dilations_[static_cast<std::size_t>(c.dilation_index)], s);
    combine(s, c, out.data());
}

namespace {
// Proportion of values above the bias; the count is a vectorisable reduction.
inline float ppv(const float* v, std::size_t n, float bias) {
    int count = 0;
    for (std::size_t t = 0; t < n; ++t) count += v[t] > bias ? 1 : 0;
    return static_cast<float>(count) / static_cast<float>(n);
}
}  // namespace

void Transform::transform_one(std::span<const float> series, std::span<float> out) const {
    Scratch s;
    s.conv.resize(length_);
    int current = -1;
    for (const auto& c : combinations_) {
        if (c.dilation_index != current) {
            current = c.dilation_index;
            dilation_bases(series, dilations_[static_cast<std::size_t>(current)], s);
        }
        combine(s, c, s.conv.data());
        // Unpadded combinations keep only the outputs whose window lies inside the series.
        const std::size_t pad =
            c.padded ? 0 : static_cast<std::size_t>(kKernelLength / 2 * dilations_[static_cast<std::size_t>(current)]);
        const float* v = s.conv.data() + pad;
        const std::size_t n = length_ - 2 * pad;
        for (int f = 0; f < c.features; ++f) {
            const auto i = static_cast<std::size_t>(c.first_feature + f);
            out[i] = ppv(v, n, biases_[i]);
        }
    }
}

void Transform::transform(std::span<const float> series, std::size_t rows, std::span<float> out,
                          unsigned threads) const {
    const std::size_t width = channels_ * length_, nf = features();
    parallel_for(rows, resolve_threads(threads), [&](std::size_t b, std::size_t e) {
        for (std::size_t r = b; r < e; ++r)
            transform_one(series.subspan(r * width, width), out.subspan(r * nf, nf));
    });
}

}  // namespace rollsense::minirocket
