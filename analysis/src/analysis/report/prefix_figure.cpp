#include "analysis/report/prefix_figure.hpp"

#include <algorithm>

#include "analysis/report/svg.hpp"

namespace rollsense::report {
namespace {

const char* const kColours[] = {"#2e6fb7", "#c0392b", "#27ae60", "#8e44ad", "#d35400", "#16a085"};
const char* const kDashes[] = {"", "6 3", "2 3", "8 3 2 3"};

// One chart: x = fraction (seconds_axis false) or seconds; one line per classifier
// (colour) and, per speed, one dash pattern; `overall` draws the all-speed curve.
std::string chart(const learn::PrefixCurves& pc, bool seconds_axis, const std::string& id) {
    const double left = 55.0, right = 190.0, top = 20.0, plot_w = 480.0, plot_h = 260.0;
    Svg svg(left + plot_w + right, top + plot_h + 55.0, id,
            seconds_axis ? "Accuracy against seconds of rolling after the clock's zero"
                         : "Accuracy against the share of the roll on the contact's clock");
    double x_max = 1.0;
    if (seconds_axis) {
        x_max = 0.0;
        for (const auto& n : pc.nominal) x_max = std::max(x_max, n.seconds);
        if (x_max <= 0.0) x_max = 1.0;
    }
    const LinearScale x{0.0, x_max, left, left + plot_w}, y{0.0, 1.0, top + plot_h, top};
    const Stroke axis{"#444", 1.0, ""}, grid{"#ddd", 1.0, ""};
    for (int k = 0; k <= 5; ++k) {
        const double v = k / 5.0;
        svg.line(left, y(v), left + plot_w, y(v), grid);
        svg.text(left - 6.0, y(v) + 4.0, fixed(100.0 * v, 0), {11.0, Anchor::end});
        const double xv = x_max * k / 5.0;
        svg.line(x(xv), top + plot_h, x(xv), top + plot_h + 5.0, axis);
        svg.text(x(xv), top + plot_h + 18.0, seconds_axis ? fixed(xv, 1) : fixed(100.0 * xv, 0),
                 {11.0, Anchor::middle});
    }
    svg.line(left, top + plot_h, left + plot_w, top + plot_h, axis);
    svg.line(left, top, left, top + plot_h, axis);
    svg.text(left + plot_w / 2.0, top + plot_h + 38.0,
             seconds_axis ? "seconds after the clock's zero (fraction \u00d7 the speed's nominal duration after it)"
                          : "% of the nominal roll, on the contact's clock",
             {12.0, Anchor::middle});
    double ly = top + 10.0;
    for (std::size_t c = 0; c < pc.classifiers.size(); ++c) {
        const auto& curve = pc.classifiers[c];
        const std::string colour = kColours[c % std::size(kColours)];
        auto draw = [&](const std::vector<learn::PrefixPoint>& pts, const std::string& dash, double width,
                        const std::string& label) {
            std::vector<std::pair<double, double>> line;
            for (const auto& p : pts) line.emplace_back(x(seconds_axis ? p.seconds : p.fraction), y(p.accuracy()));
            svg.polyline(line, {colour, width, dash});
            for (const auto& [px, py] : line) svg.circle(px, py, 2.0, colour, {colour, 0.5, ""});
            svg.line(left + plot_w + 10.0, ly, left + plot_w + 34.0, ly, {colour, width, dash});
            svg.text(left + plot_w + 38.0, ly + 4.0, label, {10.0, Anchor::start});
            ly += 15.0;
        };
        if (!seconds_axis) draw(curve.points, "", 2.5, curve.classifier + ", all speeds");
        for (std::size_t s = 0; s < curve.by_speed.size(); ++s)
            draw(curve.by_speed[s].points, kDashes[(s + (seconds_axis ? 0 : 1)) % std::size(kDashes)],
                 seconds_axis ? 2.0 : 1.0, curve.classifier + ", speed " + curve.by_speed[s].speed);
    }
    return svg.str();
}

std::string cell(const std::string& text) { return "<td class=\"num\">" + escape_xml(text) + "</td>"; }

}  // namespace

std::string prefix_section(const learn::PrefixCurves& pc) {
    std::string body = "<p class=\"note\"><strong>" + escape_xml(learn::kPrefixTimingNote) + "</strong></p>\n";
    body += "<p>A prefix is cut on the contact's own clock: the recording up to a fraction of the nominal roll "
            "(" + fixed(pc.units, 2) + " clock units, the median over this dataset's trials), counted from the "
            "half-way rise of the first touched sensor's bump in units of its full width at half maximum (after the clock's "
            "zero, a roll lasts in the median:";
    for (const auto& n : pc.nominal)
        body += " speed " + escape_xml(n.speed) + " " + fixed(n.samples, 0) + " samples, " + fixed(n.seconds, 2) +
                "\u00a0s;";
    body.back() = ')';
    body += ". For each fraction the classifiers are trained on the training folds' prefixes and tested on the test "
            "fold's (" + std::to_string(pc.repeats) + " \u00d7 " + std::to_string(pc.folds) +
            "-fold, the evaluation's partitions). A prefix that gives a classifier no input (bagged trees: fewer than "
            "three valid peaks; MiniRocket: refused by the series rule) is \u201cno decision\u201d and counts as "
            "wrong.</p>\n";
    body += "<figure>\n" + chart(pc, false, "fig-prefix-fraction") +
            "<figcaption>Accuracy against the share of the roll on the contact's clock; thick: all speeds; thin: each "
            "speed, its own dash pattern (the legend names them).</figcaption>\n</figure>\n";
    body += "<figure>\n" + chart(pc, true, "fig-prefix-seconds") +
            "<figcaption>Accuracy against seconds of rolling after the clock's zero, per classifier and speed.</figcaption>\n</figure>\n";
    body += "<table class=\"numbers\" id=\"prefix-table\"><thead><tr><th>classifier</th><th>speed</th>";
    for (double f : pc.fractions) body += "<th>" + fixed(100.0 * f, 0) + "\u00a0%</th>";
    body += "<th>95\u00a0% of full-roll accuracy at</th></tr></thead><tbody>\n";
    for (const auto& c : pc.classifiers) {
        body += "<tr><td>" + escape_xml(c.classifier) + "</td><td>all</td>";
        for (const auto& p : c.points) body += cell(percent(p.accuracy()));
        body += cell(c.fraction_95 ? fixed(100.0 * *c.fraction_95, 0) + "\u00a0% of the roll" : "never") + "</tr>\n";
        body += "<tr><td>" + escape_xml(c.classifier) + "</td><td>no decision</td>";
        for (const auto& p : c.points)
            body += cell(percent(p.total ? static_cast<double>(p.no_decision) / static_cast<double>(p.total) : 0.0));
        body += "<td></td></tr>\n";
        for (const auto& s : c.by_speed) {
            body += "<tr><td>" + escape_xml(c.classifier) + "</td><td>speed " + escape_xml(s.speed) + "</td>";
            for (const auto& p : s.points) body += cell(percent(p.accuracy()));
            body += "<td></td></tr>\n";
        }
    }
    return body + "</tbody></table>\n";
}

}  // namespace rollsense::report
