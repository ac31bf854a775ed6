// The catalogue of objects (share/objects/*.csv), in one place for everything
// that needs to know the objects: the simulation rolls them, the paper's
// analyses and the report group and draw them by shape.
//
// One CSV row per object; the columns are documented in docs/simulation.md
// ("Object catalogue"). A user adds an object by adding a row. Every error names
// the file, the line and the column, and says what would be accepted.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense {

struct ObjectSpec {
    std::string id;           // catalogue id, e.g. "C1"; what TrialInfo::object names
    std::string base;         // "circle", "square", "pentagon", ... as written in the file
    int sides = 0;            // 0 for a circle, >= 3 for a regular polygon
    double side = 0.0;        // base edge length a, mm (polygons)
    double diameter = 0.0;    // circle: diameter; polygon: circumscribed diameter, mm
    double edge_radius_min = 0.0;  // rounding of the lateral edges, mm (polygons)
    double edge_radius_max = 0.0;
    std::string description;

    bool is_cylinder() const { return sides == 0; }
    double circumradius() const { return 0.5 * diameter; }
    // Width between the fingers when a face lies flat on one of them (inscribed
    // diameter for even n, inradius + circumradius for odd n), mm.
    double flat_width() const;
};

// The ranges every object must lie in, whoever built it (the catalogue reader
// checks each row against them; the sim checks again before rolling one):
// lengths finite in (0, 200] mm (the hand opens far less; beyond, the sim's
// stepping would take minutes per trial), sides 0 or 3..12, edge radii finite,
// 0 <= min <= max below the face's inradius limit, id 1..40 characters of
// [A-Za-z0-9._-] (it becomes part of trial ids, hence of file names).
inline constexpr int kMinSides = 3;
inline constexpr int kMaxSides = 12;
inline constexpr double kMaxObjectSizeMm = 200.0;
inline constexpr std::size_t kMaxObjectIdLength = 40;

struct ObjectProblem {
    std::string column;   // the catalogue column at fault, e.g. "edge_radius_max_mm"
    std::string message;  // what is wrong and what is accepted
};
// The first way `o` lies outside those ranges, or nullopt.
std::optional<ObjectProblem> object_problem(const ObjectSpec& o);

class ObjectCatalogue {
public:
    static Result<ObjectCatalogue> load(const std::filesystem::path& file);

    const std::vector<ObjectSpec>& objects() const { return objects_; }
    const std::filesystem::path& path() const { return path_; }
    // nullptr if absent.
    const ObjectSpec* find(const std::string& id) const;
    // "C1, C2, ..." for messages.
    std::string ids() const;

private:
    std::filesystem::path path_;
    std::vector<ObjectSpec> objects_;
};

// Number of sides for a base name ("circle" = 0, "square" = 4, ...); -1 if unknown.
int sides_for_base(const std::string& base);

// The stock catalogue, relative to the share folder (the sim sensor's default
// 'catalogue' parameter).
inline constexpr const char* kStockCatalogue = "objects/paper_table2.csv";

// The share folder this installation reads: $ROLLSENSE_SHARE if set, else
// <prefix>/share/rollsense next to the installed library, else the source
// tree's share/ (a build that was not installed). The same rule as the
// rollsense program's.
std::filesystem::path default_share_dir();

}  // namespace rollsense
