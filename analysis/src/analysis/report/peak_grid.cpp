#include "analysis/report/peak_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "analysis/report/object_order.hpp"
#include "analysis/report/plotted_trial.hpp"
#include "analysis/report/svg.hpp"

namespace rollsense::report {

const char* channel_colour(std::size_t channel) {
    static const char* colours[] = {"#1f5fa8", "#c8371e", "#2b8a3e"};
    return colours[channel % 3];
}

std::vector<std::string> sorted_speeds(std::vector<std::string> speeds) {
    auto numeric = [](const std::string& s, double& v) {
        char* end = nullptr;
        v = std::strtod(s.c_str(), &end);
        return !s.empty() && end == s.c_str() + s.size();
    };
    bool all_numbers = true;
    double v = 0.0;
    for (const auto& s : speeds) all_numbers = all_numbers && numeric(s, v);
    std::sort(speeds.begin(), speeds.end(), [&](const std::string& a, const std::string& b) {
        if (!all_numbers) return a < b;
        double x = 0.0, y = 0.0;
        numeric(a, x);
        numeric(b, y);
        return x < y;
    });
    speeds.erase(std::unique(speeds.begin(), speeds.end()), speeds.end());
    return speeds;
}

TrialSelection select_trials(const DatasetReader& dataset, const std::vector<features::FeatureRow>& rows,
                             const std::vector<learn::ObjectShape>& catalogue) {
    std::map<std::string, bool> clean;
    for (const auto& r : rows) clean[r.trial_id] = r.clean;
    std::set<std::string> objects;
    std::vector<std::string> speeds;
    for (const auto& t : dataset.trials()) {
        objects.insert(t.info.object);
        speeds.push_back(t.info.speed);
    }
    TrialSelection sel;
    std::vector<std::string> classes(objects.begin(), objects.end());
    for (std::size_t i : order_objects(classes, catalogue).order) sel.objects.push_back(classes[i]);
    sel.speeds = sorted_speeds(std::move(speeds));
    sel.trial.assign(sel.objects.size(), std::vector<long>(sel.speeds.size(), -1));
    std::map<std::pair<std::string, std::string>, std::pair<std::size_t, std::size_t>> where;
    for (std::size_t o = 0; o < sel.objects.size(); ++o)
        for (std::size_t s = 0; s < sel.speeds.size(); ++s) where[{sel.objects[o], sel.speeds[s]}] = {o, s};
    // Best so far per cell: clean beats rejected, then the lowest repetition.
    std::vector<std::vector<std::pair<bool, int>>> best(sel.objects.size(),
                                                        std::vector<std::pair<bool, int>>(sel.speeds.size()));
    const auto& trials = dataset.trials();
    for (std::size_t i = 0; i < trials.size(); ++i) {
        const auto [o, s] = where.at({trials[i].info.object, trials[i].info.speed});
        const auto it = clean.find(trials[i].info.id);
        const bool ok = it != clean.end() && it->second;
        const std::pair<bool, int> key{!ok, trials[i].info.repetition};
        if (sel.trial[o][s] < 0 || key < best[o][s]) {
            sel.trial[o][s] = static_cast<long>(i);
            best[o][s] = key;
        }
    }
    return sel;
}

namespace {

// The part of the trial worth looking at: from a little before the first peak
// starts to a little after the last one ends, as a fraction of that span.
std::pair<std::size_t, std::size_t> view_window(const PlottedTrial& t) {
    const std::size_t n = t.x.size();
    std::size_t a = n, b = 0;
    for (const auto& c : t.features.channels) {
        if (c.peak.max <= 0.0) continue;
        a = std::min(a, c.peak.first);
        b = std::max(b, c.peak.last);
    }
    if (a >= b || b >= n) return {0, n == 0 ? 0 : n - 1};
    const std::size_t pad = std::max<std::size_t>(2, (b - a) / 6);
    return {a > pad ? a - pad : 0, std::min(n - 1, b + pad)};
}

}  // namespace

Result<std::string> peak_grid_figure(const DatasetReader& dataset, const TrialSelection& sel,
                                     const features::FeatureSettings& settings, const std::string& id) {
    // Each cell has its own ticks: x below it, y left of it (amplitude is scaled per plot).
    const double cell_w = 230.0, cell_h = 120.0, gap = 40.0, row_gap = 26.0, ytick_w = 34.0;
    double widest_object = 0.0;
    for (const auto& o : sel.objects) widest_object = std::max(widest_object, text_width(o, 14.0));
    const double left = ytick_w + 12.0 + std::max(14.0, widest_object), top = 56.0;
    const double cols = static_cast<double>(sel.speeds.size()), rows = static_cast<double>(sel.objects.size());
    const double width = left + cols * (cell_w + gap) + 10.0;
    const double height = top + rows * (cell_h + row_gap) + 30.0;
    Svg svg(width, height, id, "Smoothed peaks of selected trials, three channels, normalised time");

    // Legend and column headings.
    for (std::size_t c = 0; c < 3; ++c) {
        const double x = left + 110.0 * static_cast<double>(c);
        svg.line(x, 14.0, x + 24.0, 14.0, {channel_colour(c), 2.5, {}});
        svg.text(x + 30.0, 18.0, "ch" + std::to_string(c + 1), {12.0});
    }
    for (std::size_t s = 0; s < sel.speeds.size(); ++s)
        svg.text(left + static_cast<double>(s) * (cell_w + gap) + cell_w / 2.0, top - 10.0, "speed " + sel.speeds[s],
                 {13.0, Anchor::middle, true});

    const auto& trials = dataset.trials();
    std::string axis_labels;  // from the first trial drawn: the same for every plot
    int letter = 0;
    for (std::size_t o = 0; o < sel.objects.size(); ++o) {
        const double y0 = top + static_cast<double>(o) * (cell_h + row_gap);
        svg.text(left - ytick_w - 8.0, y0 + cell_h / 2.0 + 5.0, sel.objects[o], {14.0, Anchor::end, true});
        for (std::size_t s = 0; s < sel.speeds.size(); ++s) {
            const double x0 = left + static_cast<double>(s) * (cell_w + gap);
            svg.open_group("peak-plot");
            const long idx = sel.trial[o][s];
            // A trial whose file cannot be read was skipped by the features
            // (its reason is in the accuracy section): an empty cell, not a failed report.
            auto t = idx < 0 ? Result<PlottedTrial>(Error{ErrorCode::not_found, ""})
                             : load_plotted_trial(dataset, trials[static_cast<std::size_t>(idx)], settings);
            if (!t) {
                const Stroke none{"#ccc", 1.0, "4 3"};
                svg.rect(x0, y0, cell_w, cell_h, "#fafafa", &none);
                svg.text(x0 + cell_w / 2.0, y0 + cell_h / 2.0, idx < 0 ? "no trial recorded" : "trial file unreadable",
                         {11.0, Anchor::middle, false, "#777"});
                svg.close_group();
                continue;
            }
            const auto [a, b] = view_window(*t);
            double lo = 0.0, hi = std::numeric_limits<double>::lowest();
            for (const auto& ch : t->smoothed)
                for (std::size_t i = a; i <= b && i < ch.size(); ++i) {
                    if (!std::isfinite(ch[i])) continue;
                    lo = std::min(lo, ch[i]);
                    hi = std::max(hi, ch[i]);
                }
            if (!(hi > lo)) hi = lo + 1.0;
            const Stroke frame = t->features.clean ? Stroke{"#999", 0.8, {}} : Stroke{"#c8371e", 1.2, "5 3"};
            svg.rect(x0, y0, cell_w, cell_h, t->features.clean ? "#fff" : "#fff6f4", &frame);
            const LinearScale sx{t->x[a], t->x[b], x0 + 4.0, x0 + cell_w - 4.0};
            const LinearScale sy{lo, hi * 1.08, y0 + cell_h - 4.0, y0 + 4.0};
            for (std::size_t c = 0; c < features::kChannels; ++c) {
                std::vector<std::pair<double, double>> pts;
                for (std::size_t i = a; i <= b && i < t->smoothed[c].size(); ++i)
                    if (std::isfinite(t->smoothed[c][i])) pts.emplace_back(sx(t->x[i]), sy(t->smoothed[c][i]));
                svg.polyline(pts, {channel_colour(c), 1.6, {}});
            }
            const Stroke tick{"#666", 0.8, {}};
            const auto xt = nice_ticks(t->x[a], t->x[b], 4);
            for (const double v : xt) {
                svg.line(sx(v), y0 + cell_h, sx(v), y0 + cell_h + 3.0, tick);
                svg.text(sx(v), y0 + cell_h + 12.0, tick_label(v, xt.size() > 1 ? xt[1] - xt[0] : 1.0),
                         {9.0, Anchor::middle, false, "#444"});
            }
            const auto yt = nice_ticks(lo, hi * 1.08, 3);
            for (const double v : yt) {
                svg.line(x0 - 3.0, sy(v), x0, sy(v), tick);
                svg.text(x0 - 5.0, sy(v) + 3.0, tick_label(v, yt.size() > 1 ? yt[1] - yt[0] : 1.0),
                         {9.0, Anchor::end, false, "#444"});
            }
            if (axis_labels.empty()) axis_labels = t->x_label + " (x), " + t->y_label + " (y)";
            // A…Z, then AA, AB, … as a spreadsheet labels columns.
            std::string tag;
            for (int k = letter + 1; k > 0; k = (k - 1) / 26) tag.insert(tag.begin(), static_cast<char>('A' + (k - 1) % 26));
            ++letter;
            svg.text(x0 + 6.0, y0 + 15.0, tag, {12.0, Anchor::start, true});
            svg.text(x0 + cell_w - 6.0, y0 + 15.0, t->info.id, {10.0, Anchor::end, false, "#555"});
            if (!t->features.clean)
                svg.text(x0 + cell_w - 6.0, y0 + cell_h - 8.0, "rejected", {10.0, Anchor::end, true, "#c8371e"});
            svg.close_group();
        }
    }
    svg.text(left + cols * (cell_w + gap) / 2.0, height - 10.0,
             (axis_labels.empty() ? std::string() : axis_labels + "; ") +
                 "each plot spans its trial's peaks, amplitude scaled per plot",
             {11.0, Anchor::middle, false, "#444"});
    return svg.str();
}

}  // namespace rollsense::report
