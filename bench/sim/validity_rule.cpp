#include "validity_rule.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

namespace rollsense::sim::bench {

// Power spectrum by a plain DFT of the mean-removed, zero-padded series. N is at
// most a few hundred samples, so O(N²) is fine for a bench.
int smoothing_window(const std::vector<double>& x, double factor) {
    const std::size_t n = x.size();
    if (n < 2) return 1;
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(n);
    const std::size_t m = 2 * n;
    std::vector<double> power(n);
    double total = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        double re = 0.0, im = 0.0;
        for (std::size_t t = 0; t < n; ++t) {
            const double a = -2.0 * 3.14159265358979323846 * static_cast<double>(k * t % m) / static_cast<double>(m);
            re += (x[t] - mean) * std::cos(a);
            im += (x[t] - mean) * std::sin(a);
        }
        power[k] = (re * re + im * im) / static_cast<double>(m);
        total += power[k];
    }
    if (!(total > 0.0)) return 1;
    const double tau = 1.0 - factor;
    double cum = 0.0;
    std::size_t rho = n;
    for (std::size_t k = 0; k < n; ++k) {
        cum += power[k] / total;
        if (cum > tau) {
            rho = k + 1;
            break;
        }
    }
    const double r = static_cast<double>(std::max<std::size_t>(rho - 1, 1));
    const double w = std::ceil(std::sqrt(std::pow(0.44294 * static_cast<double>(m) / r, 2) + 1.0));
    return static_cast<int>(std::min(w, static_cast<double>(m)));
}

std::vector<double> smoothdata_gaussian(const std::vector<double>& x, double factor) {
    return gaussian_smooth(x, smoothing_window(x, factor));
}

std::vector<double> gaussian_smooth(const std::vector<double>& x, int w) {
    if (w < 2) return x;
    const double sigma = w / 5.0;
    const int lo = -(w / 2), hi = (w + 1) / 2 - 1;
    const int n = static_cast<int>(x.size());
    std::vector<double> y(x.size());
    for (int i = 0; i < n; ++i) {
        double s = 0.0, g = 0.0;
        for (int e = lo; e <= hi; ++e) {
            const int j = i + e;
            if (j < 0 || j >= n) continue;
            const double weight = std::exp(-static_cast<double>(e * e) / (2.0 * sigma * sigma));
            s += weight * x[static_cast<std::size_t>(j)];
            g += weight;
        }
        y[static_cast<std::size_t>(i)] = s / g;
    }
    return y;
}

PeakInfo find_peak(const std::vector<double>& y, double fraction, double min_amplitude) {
    PeakInfo p;
    const int n = static_cast<int>(y.size());
    if (n == 0) return p;
    p.imax = static_cast<int>(std::max_element(y.begin(), y.end()) - y.begin());
    p.amplitude = y[static_cast<std::size_t>(p.imax)];
    p.above_threshold = p.amplitude > min_amplitude;
    const double level = fraction * p.amplitude;
    int s = p.imax;
    while (s > 0 && y[static_cast<std::size_t>(s - 1)] >= level) --s;
    int e = p.imax;
    while (e < n - 1 && y[static_cast<std::size_t>(e + 1)] >= level) ++e;
    p.start = s;
    p.end = e;
    p.complete_start = s > 0;
    p.complete_end = e < n - 1;
    // Half-width: outermost samples >= 50 % inside the peak.
    int h0 = -1, h1 = -1;
    for (int i = s; i <= e; ++i)
        if (y[static_cast<std::size_t>(i)] >= 0.5 * p.amplitude) {
            if (h0 < 0) h0 = i;
            h1 = i;
        }
    p.half_width = h0 < 0 ? 0.0 : h1 - h0;
    return p;
}

TrialVerdict judge_trial(const std::array<std::vector<double>, 3>& raw) {
    TrialVerdict v;
    v.clean = true;
    for (std::size_t c = 0; c < 3; ++c) {
        const auto y = smoothdata_gaussian(raw[c]);
        v.peaks[c] = find_peak(y);
        const auto& p = v.peaks[c];
        if (!p.above_threshold) v.all_above_threshold = false;
        std::string why;
        if (!p.above_threshold) why = "low_amplitude";
        else if (!p.complete_start) why = "incomplete_start";
        else if (!p.complete_end) why = "incomplete_end";
        else if (p.end == p.start) why = "zero_width";
        if (!why.empty()) {
            v.clean = false;
            v.reason += (v.reason.empty() ? "" : "; ") + std::string("ch") + std::to_string(c + 1) + " " + why;
        }
    }
    if (!v.clean) {
        v.features.fill(std::nan(""));
        return v;
    }
    const double w2 = v.peaks[1].end - v.peaks[1].start;
    for (std::size_t c = 0; c < 3; ++c) {
        const auto& p = v.peaks[c];
        const double width = p.end - p.start;
        const double mid = 0.5 * (p.start + p.end);
        v.features[c] = p.amplitude;
        v.features[3 + c] = (mid - p.imax) / width;
        v.features[6 + c] = p.half_width / w2;
    }
    v.features[9] = (v.peaks[0].end - v.peaks[0].start) / w2;
    v.features[10] = (v.peaks[2].end - v.peaks[2].start) / w2;
    v.features[11] = (v.peaks[1].imax - v.peaks[0].imax) / w2;
    v.features[12] = (v.peaks[2].imax - v.peaks[1].imax) / w2;
    return v;
}

}  // namespace rollsense::sim::bench
