// The catalogue of objects the simulation can roll (share/objects/*.csv).
//
// One CSV row per object; the columns are documented in docs/simulation.md
// ("Object catalogue"). A user adds an object by adding a row. Every error names
// the file, the line and the column, and says what would be accepted.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::sim {

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

}  // namespace rollsense::sim
