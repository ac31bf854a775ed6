#include "analysis/report/confusion_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/report/object_order.hpp"
#include "analysis/report/svg.hpp"

namespace rollsense::report {

namespace {

// White → deep blue; the count text turns white where the cell gets dark.
std::string shade(double fraction) {
    const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
    const int r = static_cast<int>(std::lround(255.0 - f * (255.0 - 8.0)));
    const int g = static_cast<int>(std::lround(255.0 - f * (255.0 - 69.0)));
    const int b = static_cast<int>(std::lround(255.0 - f * (255.0 - 148.0)));
    char buf[16];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", r, g, b);
    return buf;
}

}  // namespace

std::string confusion_figure(const learn::ConfusionMatrix& m, const std::vector<learn::ObjectShape>& catalogue,
                             const std::string& id, const std::string& caption) {
    const ObjectOrder ord = order_objects(m.classes, catalogue);
    const std::size_t n = m.size();
    const double cell = n > 12 ? 36.0 : 48.0;
    // Room for the names, however long: row names left of their glyphs; column
    // names above, turned 45 degrees when one is wider than a cell.
    double widest = 0.0;
    for (const auto& c : m.classes) widest = std::max(widest, text_width(c, 13.0));
    const bool turn = widest > cell - 4.0;
    const double rise = turn ? widest * 0.7072 : 0.0;  // height (and reach to the right) of a turned name
    const double left = std::max(110.0, 34.0 + widest + 36.0), top = 70.0 + rise;
    const double tpr_gap = 14.0, tpr_w = 70.0;
    const double width = left + cell * static_cast<double>(n) + tpr_gap + tpr_w + 20.0 + rise;
    const double height = top + cell * static_cast<double>(n) + 60.0;
    Svg svg(width, height, id, caption);

    const double grid_x1 = left + cell * static_cast<double>(n);
    const double grid_y1 = top + cell * static_cast<double>(n);
    svg.text((left + grid_x1) / 2.0, 22.0, "predicted object", {13.0, Anchor::middle, true});
    svg.text(22.0, (top + grid_y1) / 2.0, "true object", {13.0, Anchor::middle, true, "#000", -90.0});

    const std::vector<double> tpr = m.true_positive_rates();
    for (std::size_t r = 0; r < n; ++r) {
        const std::size_t truth = ord.order[r];
        const double y = top + cell * static_cast<double>(r);
        const double row_total = static_cast<double>(m.row_total(truth));
        svg.text(left - 34.0, y + cell / 2.0 + 4.5, m.classes[truth], {13.0, Anchor::end, true});
        draw_object_glyph(svg, m.classes[truth], catalogue, left - 18.0, y + cell / 2.0, 8.0);
        for (std::size_t c = 0; c < n; ++c) {
            const std::size_t pred = ord.order[c];
            const double x = left + cell * static_cast<double>(c);
            const std::size_t count = m.at(truth, pred);
            const double frac = row_total > 0 ? static_cast<double>(count) / row_total : 0.0;
            svg.open_group("cell");
            const Stroke thin{"#bbb", 0.5, {}};
            svg.rect(x, y, cell, cell, shade(frac), &thin);
            if (count > 0)
                svg.text(x + cell / 2.0, y + cell / 2.0 + 4.5, std::to_string(count),
                         {13.0, Anchor::middle, truth == pred, frac > 0.55 ? "#fff" : "#000"});
            svg.close_group();
        }
        // True-positive rate of the row, shaded like a cell.
        const double tx = grid_x1 + tpr_gap;
        const Stroke thin{"#bbb", 0.5, {}};
        svg.rect(tx, y, tpr_w, cell, shade(tpr[truth]), &thin);
        svg.text(tx + tpr_w / 2.0, y + cell / 2.0 + 4.5, percent(tpr[truth]),
                 {12.0, Anchor::middle, false, std::isfinite(tpr[truth]) && tpr[truth] > 0.55 ? "#fff" : "#000"});
    }
    for (std::size_t c = 0; c < n; ++c) {
        const double x = left + cell * static_cast<double>(c);
        if (turn)
            svg.text(x + cell / 2.0, top - 26.0, m.classes[ord.order[c]], {13.0, Anchor::start, true, "#000", -45.0});
        else
            svg.text(x + cell / 2.0, top - 26.0, m.classes[ord.order[c]], {13.0, Anchor::middle, true});
        draw_object_glyph(svg, m.classes[ord.order[c]], catalogue, x + cell / 2.0, top - 12.0, 7.0);
    }
    svg.text(grid_x1 + tpr_gap + tpr_w / 2.0, top - 12.0, "TPR", {13.0, Anchor::middle, true});

    // Block boundaries (the paper's thicker lines) and the outer frame.
    const Stroke thick{"#000", 2.5, {}};
    double offset = 0.0;
    for (std::size_t g = 0; g <= ord.groups.size(); ++g) {
        const double p = left + cell * offset;
        const double q = top + cell * offset;
        svg.line(p, top, p, grid_y1, thick);
        svg.line(left, q, grid_x1, q, thick);
        if (g < ord.groups.size()) offset += static_cast<double>(ord.groups[g].members.size());
    }
    const Stroke frame{"#000", 1.5, {}};
    svg.rect(grid_x1 + tpr_gap, top, tpr_w, grid_y1 - top, "none", &frame);

    // Group names under the matrix, one per block.
    offset = 0.0;
    for (const auto& g : ord.groups) {
        const double w = cell * static_cast<double>(g.members.size());
        svg.text(left + cell * offset + w / 2.0, grid_y1 + 20.0, g.label, {11.0, Anchor::middle});
        offset += static_cast<double>(g.members.size());
    }
    char total[96];
    std::snprintf(total, sizeof total, "%zu of %zu correct (%s)", m.correct(), m.total(), percent(m.accuracy()).c_str());
    svg.text((left + grid_x1) / 2.0, grid_y1 + 44.0, total, {12.0, Anchor::middle});
    return svg.str();
}

}  // namespace rollsense::report
