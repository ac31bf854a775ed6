#include "analysis/report/feature_figure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/report/peak_grid.hpp"
#include "analysis/report/svg.hpp"

namespace rollsense::report {

std::optional<std::size_t> pick_feature_trial(const DatasetReader& dataset,
                                              const std::vector<features::FeatureRow>& rows,
                                              const std::vector<learn::ObjectShape>& catalogue) {
    const TrialSelection sel = select_trials(dataset, rows, catalogue);
    std::vector<bool> clean_by_index(dataset.trials().size(), false);
    std::map<std::string, bool> clean;
    for (const auto& r : rows) clean[r.trial_id] = r.clean;
    for (std::size_t i = 0; i < dataset.trials().size(); ++i) {
        auto it = clean.find(dataset.trials()[i].info.id);
        clean_by_index[i] = it != clean.end() && it->second;
    }
    for (std::size_t o = 0; o < sel.objects.size(); ++o) {
        // Middle speed first, then outwards.
        const std::size_t n = sel.speeds.size();
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t s = (n / 2 + k) % n;
            const long idx = sel.trial[o][s];
            if (idx >= 0 && clean_by_index[static_cast<std::size_t>(idx)]) return static_cast<std::size_t>(idx);
        }
    }
    return std::nullopt;
}

std::string feature_figure(const PlottedTrial& t, const std::string& id) {
    const double width = 1000.0, height = 520.0;
    const double left = 60.0, right = 30.0, top = 110.0, bottom = 110.0;
    Svg svg(width, height, id, "The 13 features of trial " + t.info.id + " drawn on its smoothed peaks");
    const auto& ch = t.features.channels;

    std::size_t a = t.x.size(), b = 0;
    double hi = 0.0;
    for (const auto& c : ch) {
        a = std::min(a, c.peak.first);
        b = std::max(b, c.peak.last);
        hi = std::max(hi, c.peak.max);
    }
    if (t.x.empty()) return svg.str();
    b = std::min(b, t.x.size() - 1);
    if (a >= b) a = 0, b = t.x.size() - 1;
    const std::size_t pad = std::max<std::size_t>(3, (b - a) / 8);
    a = a > pad ? a - pad : 0;
    b = std::min(t.x.size() - 1, b + pad);
    double lo = 0.0;
    for (const auto& s : t.smoothed)
        for (std::size_t i = a; i <= b && i < s.size(); ++i)
            if (std::isfinite(s[i])) lo = std::min(lo, s[i]);
    if (!(hi > lo)) hi = lo + 1.0;
    const LinearScale sx{t.x[a], t.x[b], left, width - right};
    const LinearScale sy{lo, hi * 1.05, height - bottom, top};

    // Axes.
    const Stroke axis{"#444", 1.0, {}};
    svg.line(left, height - bottom, width - right, height - bottom, axis);
    svg.line(left, top - 10.0, left, height - bottom, axis);
    svg.line(left, sy(0.0), width - right, sy(0.0), {"#bbb", 0.8, "2 3"});
    svg.text((left + width - right) / 2.0, height - 14.0, t.x_label + "; only ratios of times become features",
             {12.0, Anchor::middle});
    svg.text(14.0, (top + height - bottom) / 2.0, t.y_label, {12.0, Anchor::middle, false, "#000", -90.0});
    const auto xt = nice_ticks(t.x[a], t.x[b], 8);
    for (const double v : xt) {
        svg.line(sx(v), height - bottom, sx(v), height - bottom + 5.0, axis);
        svg.text(sx(v), height - bottom + 16.0, tick_label(v, xt.size() > 1 ? xt[1] - xt[0] : 1.0), {11.0, Anchor::middle});
    }
    const auto yt = nice_ticks(lo, hi * 1.05, 5);
    for (const double v : yt) {
        svg.line(left - 5.0, sy(v), left, sy(v), axis);
        svg.text(left - 7.0, sy(v) + 4.0, tick_label(v, yt.size() > 1 ? yt[1] - yt[0] : 1.0), {11.0, Anchor::end});
    }

    for (std::size_t c = 0; c < features::kChannels; ++c) {
        std::vector<std::pair<double, double>> pts;
        for (std::size_t i = a; i <= b && i < t.smoothed[c].size(); ++i)
            if (std::isfinite(t.smoothed[c][i])) pts.emplace_back(sx(t.x[i]), sy(t.smoothed[c][i]));
        svg.polyline(pts, {channel_colour(c), 2.2, {}});
    }

    const std::string cn[3] = {"1", "2", "3"};
    for (std::size_t c = 0; c < features::kChannels; ++c) {
        const auto& p = ch[c];
        const std::string colour = channel_colour(c);
        const Stroke mark{colour, 1.4, {}};
        const Stroke dashed{colour, 1.2, "4 3"};
        // Amplitude: from zero to the maximum at the time of the maximum.
        const double xm = sx(p.t_max);
        svg.arrow(xm, sy(0.0), xm, sy(p.amplitude), dashed, false, true);
        svg.text(xm + 4.0, sy(p.amplitude) - 6.0, "F" + cn[c] + " amplitude", {11.0, Anchor::start, true, colour});
        // Width: the 5 % crossings, one band per channel under the axis; the
        // skewness compares its mid-point (tick) with the maximum.
        const double level5 = height - bottom + 30.0 + 17.0 * static_cast<double>(c);  // below the tick labels
        svg.line(sx(p.t_start), sy(p.peak.max * 0.05), sx(p.t_start), level5, {colour, 0.8, "2 2"});
        svg.line(sx(p.t_end), sy(p.peak.max * 0.05), sx(p.t_end), level5, {colour, 0.8, "2 2"});
        svg.arrow(sx(p.t_start), level5, sx(p.t_end), level5, mark, true, true);
        const std::string width_label = c == 0 ? "width ch1 (F10 = width ch1 / width ch2)"
                                        : c == 1 ? "width ch2 (the divisor of F7–F13)"
                                                 : "width ch3 (F11 = width ch3 / width ch2)";
        // Right of the bar if it fits, else left of it (about 5.5 px per character).
        const double label_w = 5.5 * static_cast<double>(width_label.size());
        if (sx(p.t_end) + 6.0 + label_w < width)
            svg.text(sx(p.t_end) + 6.0, level5 + 4.0, width_label, {10.0, Anchor::start, false, colour});
        else
            svg.text(sx(p.t_start) - 6.0, level5 + 4.0, width_label, {10.0, Anchor::end, false, colour});
        const double mid = sx(0.5 * (p.t_start + p.t_end));
        svg.line(mid, level5 - 5.0, mid, level5 + 5.0, {colour, 2.0, {}});
        // Half-width: the extent at or above half the maximum.
        const auto [h0, h1] = half_maximum_span(t.smoothed[c], p);
        const double y50 = sy(0.5 * p.peak.max);
        svg.arrow(sx(t.x[h0]), y50, sx(t.x[h1]), y50, mark, true, true);
        svg.text(sx(t.x[h1]) + 4.0, y50 - 3.0, "F" + std::to_string(7 + c) + " half-width",
                 {10.0, Anchor::start, false, colour});
        // Skewness label next to the maximum: (mid-point − t_max) / width.
        svg.text(xm + 9.0, sy(p.amplitude) + 9.0, "F" + std::to_string(4 + c) + " skew " + fixed(p.skewness, 2),
                 {10.0, Anchor::start, false, colour});
    }
    // Time between maxima, above the peaks.
    const Stroke between{"#222", 1.4, {}};
    const double y12 = top - 60.0, y13 = top - 34.0;
    for (std::size_t c = 0; c < features::kChannels; ++c)
        svg.line(sx(ch[c].t_max), top - 70.0, sx(ch[c].t_max), sy(ch[c].amplitude), {"#999", 0.8, "2 3"});
    svg.arrow(sx(ch[0].t_max), y12, sx(ch[1].t_max), y12, between, true, true);
    svg.text(0.5 * (sx(ch[0].t_max) + sx(ch[1].t_max)), y12 - 5.0, "F12 time between maxima ch1 → ch2",
             {11.0, Anchor::middle, true});
    svg.arrow(sx(ch[1].t_max), y13, sx(ch[2].t_max), y13, between, true, true);
    svg.text(0.5 * (sx(ch[1].t_max) + sx(ch[2].t_max)), y13 - 5.0, "F13 time between maxima ch2 → ch3",
             {11.0, Anchor::middle, true});

    for (std::size_t c = 0; c < 3; ++c) {
        const double x = width - right - 240.0 + 80.0 * static_cast<double>(c);
        svg.line(x, 16.0, x + 22.0, 16.0, {channel_colour(c), 2.5, {}});
        svg.text(x + 27.0, 20.0, "ch" + std::to_string(c + 1), {12.0});
    }
    svg.text(left, 20.0, "trial " + t.info.id, {13.0, Anchor::start, true});
    return svg.str();
}

std::string feature_values_table(const PlottedTrial& t) {
    std::string h = "<table class=\"numbers\"><thead><tr><th>feature</th><th>meaning</th><th>value</th></tr></thead><tbody>\n";
    const auto& names = features::feature_names();
    const auto& desc = features::feature_descriptions();
    for (std::size_t i = 0; i < features::kFeatureCount; ++i)
        h += "<tr><td>" + escape_xml(names[i]) + "</td><td>" + escape_xml(desc[i]) + "</td><td class=\"num\">" +
             fixed(t.features.values[i], 4) + "</td></tr>\n";
    return h + "</tbody></table>\n";
}

}  // namespace rollsense::report
