// The paper's own analyses (method.md §6), computed for any dataset and shown
// beside the paper's numbers: clean-trial counts, cylinder vs polygon,
// cylinders misclassified, base-edge-length accuracy among polygons, and the
// pentagon ↔ hexagon confusion.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rollsense/features.hpp"
#include "rollsense/object_catalogue.hpp"
#include "analysis/learn/metrics.hpp"

namespace rollsense::learn {

struct ObjectShape {
    std::string id;    // class label, e.g. "P1"
    std::string base;  // "circle", "square", "pentagon", "hexagon", ...
    double side_mm = 0.0;  // base edge length; 0 for a circle
    bool cylinder() const { return base == "circle"; }
};

// The shapes of a catalogue's objects, in its order.
std::vector<ObjectShape> object_shapes(const ObjectCatalogue& catalogue);

// The stock catalogue (share/objects/paper_table2.csv in default_share_dir(),
// the file the sim rolls from by default: the paper's Table II plus any row a
// user adds), read once. If it cannot be read the error is logged and the list
// is empty: the analyses then leave every object out of the shape rows, and
// say so, rather than guess.
const std::vector<ObjectShape>& paper_objects();

struct PaperAnalysis {
    Count clean;                    // clean trials of all trials
    Count cylinders_clean;          // clean cylinder trials of all cylinder trials
    Count polygons_clean;
    Count accuracy;                 // correct of clean (the classification run analysed)
    Count family_correct;           // predicted cylinder/polygon family right
    Count cylinders_misclassified;  // of clean cylinder trials
    Count polygon_edge_correct;     // polygons predicted as a polygon of the same edge length
    Count hexagons_misclassified;   // of clean hexagon trials
    Count hexagons_called_pentagons;  // of misclassified hexagons
    Count pentagons_misclassified;
    Count pentagons_called_hexagons;
    std::vector<std::string> unknown_objects;  // labels not in the catalogue (left out of shape analyses)
};

// `rows`: every trial (clean and rejected); `table_rows[i]`: the index in `rows`
// of table row i; `predicted[i]`: its out-of-fold label (class_names order).
PaperAnalysis analyse_like_paper(const std::vector<features::FeatureRow>& rows,
                                 std::span<const std::size_t> table_rows, std::span<const int> truth,
                                 std::span<const int> predicted, const std::vector<std::string>& class_names,
                                 const std::vector<ObjectShape>& catalogue = paper_objects());

// The paper's figures for the same rows.
const PaperAnalysis& paper_figures();

// A side-by-side table: "figure | this data | paper".
std::string format_paper_comparison(const PaperAnalysis& ours);

}  // namespace rollsense::learn
