#include "analysis/report/object_order.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace rollsense::report {

namespace {

const learn::ObjectShape* find_shape(const std::string& id, const std::vector<learn::ObjectShape>& catalogue) {
    for (const auto& o : catalogue)
        if (o.id == id) return &o;
    return nullptr;
}

int base_rank(const std::string& base) {
    if (base == "square") return 0;
    if (base == "pentagon") return 1;
    if (base == "hexagon") return 2;
    return 3;
}

std::string edge_text(double mm) {
    return fixed(mm, mm == std::floor(mm) ? 0 : 1) + " mm";
}

}  // namespace

ObjectOrder order_objects(const std::vector<std::string>& classes, const std::vector<learn::ObjectShape>& catalogue) {
    std::vector<std::size_t> cylinders, unknown;
    std::map<double, std::vector<std::size_t>, std::greater<>> polygons_by_edge;
    for (std::size_t i = 0; i < classes.size(); ++i) {
        const auto* s = find_shape(classes[i], catalogue);
        if (!s) unknown.push_back(i);
        else if (s->cylinder()) cylinders.push_back(i);
        else polygons_by_edge[s->side_mm].push_back(i);
    }
    auto by_name = [&](std::size_t a, std::size_t b) { return classes[a] < classes[b]; };
    ObjectOrder out;
    if (!cylinders.empty()) {
        std::sort(cylinders.begin(), cylinders.end(), by_name);
        out.groups.push_back({"cylinders", cylinders});
    }
    const std::size_t edge_groups = polygons_by_edge.size();
    std::size_t rank = 0;
    for (auto& [edge, members] : polygons_by_edge) {
        std::sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) {
            const int ra = base_rank(find_shape(classes[a], catalogue)->base);
            const int rb = base_rank(find_shape(classes[b], catalogue)->base);
            return ra != rb ? ra < rb : classes[a] < classes[b];
        });
        // With the paper's two edge lengths the groups read "large" and "small".
        std::string label = "polygons (" + edge_text(edge) + ")";
        if (edge_groups == 2) label = (rank == 0 ? "large " : "small ") + label;
        out.groups.push_back({label, members});
        ++rank;
    }
    if (!unknown.empty()) {
        std::sort(unknown.begin(), unknown.end(), by_name);
        out.groups.push_back({"not in the catalogue", unknown});
    }
    for (const auto& g : out.groups) out.order.insert(out.order.end(), g.members.begin(), g.members.end());
    return out;
}

void draw_object_glyph(Svg& svg, const std::string& object, const std::vector<learn::ObjectShape>& catalogue,
                       double cx, double cy, double radius) {
    const auto* s = find_shape(object, catalogue);
    if (!s) return;
    const Stroke outline{"#333", 1.0, {}};
    if (s->cylinder()) {
        svg.circle(cx, cy, radius, "none", outline);
        return;
    }
    const int sides = s->base == "square" ? 4 : s->base == "pentagon" ? 5 : s->base == "hexagon" ? 6 : 0;
    if (sides == 0) return;
    std::vector<std::pair<double, double>> pts;
    // Flat side down, as the prism lies on the sensing finger.
    const double start = std::numbers::pi / 2.0 + std::numbers::pi / sides;
    for (int k = 0; k < sides; ++k) {
        const double a = start + 2.0 * std::numbers::pi * k / sides;
        pts.emplace_back(cx + radius * std::cos(a), cy + radius * std::sin(a));
    }
    svg.polygon(pts, "none", outline);
}

}  // namespace rollsense::report
