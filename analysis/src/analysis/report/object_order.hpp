// The order the paper shows its objects in (Fig. 9): cylinders, then the
// polygonal prisms grouped by base edge length, largest first, each group
// square → pentagon → hexagon. Objects not in the catalogue come last, in
// their own group, so any dataset still gets a complete figure.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "analysis/learn/paper_analysis.hpp"
#include "analysis/report/svg.hpp"

namespace rollsense::report {

struct ObjectGroup {
    std::string label;                 // "cylinders", "large polygons (18 mm)", ...
    std::vector<std::size_t> members;  // indices into the class list given
};

struct ObjectOrder {
    std::vector<std::size_t> order;  // display position → index into the class list
    std::vector<ObjectGroup> groups;
};

ObjectOrder order_objects(const std::vector<std::string>& classes, const std::vector<learn::ObjectShape>& catalogue);

// A small outline of the object's base (circle, square, pentagon, hexagon)
// centred at (cx, cy), as the paper draws next to the object ids. Unknown
// shapes get nothing.
void draw_object_glyph(Svg& svg, const std::string& object, const std::vector<learn::ObjectShape>& catalogue,
                       double cx, double cy, double radius);

}  // namespace rollsense::report
