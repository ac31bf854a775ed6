#include "rollsense/object_catalogue.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include "rollsense/csv.hpp"

namespace rollsense {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Circumscribed diameter of a regular n-gon of side a.
double circumscribed_diameter(int n, double a) { return a / std::sin(kPi / n); }

bool id_char(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '-';
}

}  // namespace

std::optional<ObjectProblem> object_problem(const ObjectSpec& o) {
    auto problem = [](std::string column, std::string message) {
        return std::optional<ObjectProblem>(ObjectProblem{std::move(column), std::move(message)});
    };
    // The id becomes part of trial ids and so of file names.
    if (o.id.empty() || o.id.size() > kMaxObjectIdLength || o.id.front() == '.' ||
        !std::all_of(o.id.begin(), o.id.end(), id_char))
        return problem("id", "id '" + o.id.substr(0, 2 * kMaxObjectIdLength) + "' must be 1 to " +
                                 std::to_string(kMaxObjectIdLength) +
                                 " characters of A-Z a-z 0-9 . _ - (not starting with '.')");
    if (o.sides != 0 && (o.sides < kMinSides || o.sides > kMaxSides))
        return problem("sides", "sides " + std::to_string(o.sides) + " is not 0 (circle) or " +
                                    std::to_string(kMinSides) + " to " + std::to_string(kMaxSides));
    const std::string range = " > 0 and <= " + csv::format_number(kMaxObjectSizeMm) + " mm";
    auto length_ok = [](double v) { return std::isfinite(v) && v > 0.0 && v <= kMaxObjectSizeMm; };
    for (const auto& [column, v] : {std::pair{"edge_radius_min_mm", o.edge_radius_min},
                                    std::pair{"edge_radius_max_mm", o.edge_radius_max}})
        if (!std::isfinite(v)) return problem(column, "edge radius " + csv::format_number(v) + " is not a finite number");
    if (o.is_cylinder()) {
        if (!length_ok(o.diameter))
            return problem("diameter_mm", "a circle needs diameter_mm" + range + ", not " +
                                              csv::format_number(o.diameter));
        if (o.side != 0.0) return problem("side_mm", "a circle has no side length; leave side_mm empty");
        return std::nullopt;
    }
    if (!length_ok(o.side))
        return problem("side_mm", "a " + o.base + " needs side_mm" + range + ", not " + csv::format_number(o.side));
    if (!std::isfinite(o.diameter) || o.diameter < 0.0)
        return problem("diameter_mm", "diameter " + csv::format_number(o.diameter) + " is not a finite number >= 0");
    if (o.edge_radius_min < 0.0 || o.edge_radius_max < o.edge_radius_min)
        return problem("edge_radius_max_mm", "edge radius range must satisfy 0 <= min <= max");
    // A rounding larger than this would eat a whole face.
    const double limit = 0.5 * o.side * std::tan(kPi * (0.5 - 1.0 / o.sides));
    if (o.edge_radius_max >= limit)
        return problem("edge_radius_max_mm", "edge radius " + csv::format_number(o.edge_radius_max) +
                                                 " mm is too large for a side of " + csv::format_number(o.side) +
                                                 " mm (must be below " +
                                                 csv::format_number(std::round(limit * 100) / 100) + " mm)");
    return std::nullopt;
}

int sides_for_base(const std::string& base) {
    static const std::map<std::string, int> names{{"circle", 0},  {"triangle", 3}, {"square", 4},
                                                  {"pentagon", 5}, {"hexagon", 6}, {"heptagon", 7},
                                                  {"octagon", 8}};
    auto it = names.find(base);
    return it == names.end() ? -1 : it->second;
}

double ObjectSpec::flat_width() const {
    if (is_cylinder()) return diameter;
    const double R = circumradius();
    const double inradius = R * std::cos(kPi / sides);
    return sides % 2 == 0 ? 2.0 * inradius : inradius + R;
}

const ObjectSpec* ObjectCatalogue::find(const std::string& id) const {
    for (const auto& o : objects_)
        if (o.id == id) return &o;
    return nullptr;
}

std::string ObjectCatalogue::ids() const {
    std::string out;
    for (const auto& o : objects_) out += (out.empty() ? "" : ", ") + o.id;
    return out;
}

Result<ObjectCatalogue> ObjectCatalogue::load(const std::filesystem::path& file) {
    if (!std::filesystem::exists(file))
        return Error{ErrorCode::not_found, "object catalogue " + file.string() +
                                               " does not exist; give a CSV file of objects (see docs/simulation.md, "
                                               "'Object catalogue')"};
    auto opened = csv::Reader::open(file);
    if (!opened) return opened.error();
    csv::Reader& reader = opened.value();

    struct Column {
        const char* name;
        std::size_t index = 0;
    };
    Column c_id{"id"}, c_base{"base"}, c_sides{"sides"}, c_side{"side_mm"}, c_diam{"diameter_mm"},
        c_rmin{"edge_radius_min_mm"}, c_rmax{"edge_radius_max_mm"}, c_desc{"description"};
    for (Column* c : {&c_id, &c_base, &c_sides, &c_side, &c_diam, &c_rmin, &c_rmax, &c_desc}) {
        auto idx = reader.column(c->name);
        if (!idx) return idx.error();
        c->index = idx.value();
    }

    ObjectCatalogue cat;
    cat.path_ = file;
    std::set<std::string> seen;
    std::vector<std::string> fields;
    auto bad = [&](std::size_t column, const std::string& what) {
        return Error{ErrorCode::parse_error, reader.where(column) + ": " + what};
    };
    // Empty field → value 0 ("not applicable"), otherwise a strict number.
    auto optional_number = [&](std::size_t column) -> Result<double> {
        if (fields[column].empty()) return 0.0;
        return reader.number(fields, column);
    };

    while (true) {
        auto more = reader.next(fields);
        if (!more) return more.error();
        if (!more.value()) break;

        ObjectSpec o;
        o.id = fields[c_id.index];
        if (o.id.empty()) return bad(c_id.index, "an object needs an id (e.g. C1)");
        if (!seen.insert(o.id).second) return bad(c_id.index, "id '" + o.id + "' appears twice");

        o.base = fields[c_base.index];
        const int base_sides = sides_for_base(o.base);
        if (base_sides < 0)
            return bad(c_base.index, "unknown base '" + o.base +
                                         "'; use circle, triangle, square, pentagon, hexagon, heptagon or octagon");

        // The whole-number check comes before the cast: 1e10 or NaN cast to
        // int is undefined behaviour.
        auto sides = optional_number(c_sides.index);
        if (!sides) return sides.error();
        const double n = sides.value();
        if (!(n == 0 || (n >= kMinSides && n <= kMaxSides)) || n != std::floor(n))
            return bad(c_sides.index, "sides must be a whole number, 0 for a circle or " + std::to_string(kMinSides) +
                                          " to " + std::to_string(kMaxSides) + " for a polygon");
        o.sides = static_cast<int>(n);
        if (o.sides != base_sides)
            return bad(c_sides.index, "sides " + std::to_string(o.sides) + " contradicts base '" + o.base +
                                          "' (expected " + std::to_string(base_sides) + ")");

        std::size_t column[4] = {c_side.index, c_diam.index, c_rmin.index, c_rmax.index};
        double* value[4] = {&o.side, &o.diameter, &o.edge_radius_min, &o.edge_radius_max};
        for (int i = 0; i < 4; ++i) {
            auto v = optional_number(column[i]);
            if (!v) return v.error();
            *value[i] = v.value();
        }
        o.description = fields[c_desc.index];

        // A rounded diameter in the file is replaced by the exact one.
        if (!o.is_cylinder() && o.diameter != 0.0 && std::isfinite(o.side) && o.side > 0.0) {
            const double expected = circumscribed_diameter(o.sides, o.side);
            if (std::isfinite(o.diameter) && std::abs(o.diameter - expected) > 0.2)
                return bad(c_diam.index, "circumscribed diameter " + csv::format_number(o.diameter) +
                                             " mm does not match a " + o.base + " of side " +
                                             csv::format_number(o.side) + " mm (expected " +
                                             csv::format_number(std::round(expected * 100) / 100) +
                                             " mm); fix it or leave it empty");
        }
        if (auto problem = object_problem(o)) {
            const std::size_t at = problem->column == "side_mm"               ? c_side.index
                                   : problem->column == "diameter_mm"          ? c_diam.index
                                   : problem->column == "edge_radius_min_mm"   ? c_rmin.index
                                   : problem->column == "edge_radius_max_mm"   ? c_rmax.index
                                   : problem->column == "sides"                ? c_sides.index
                                                                               : c_id.index;
            return bad(at, problem->message);
        }
        if (!o.is_cylinder()) o.diameter = circumscribed_diameter(o.sides, o.side);
        cat.objects_.push_back(std::move(o));
    }
    if (cat.objects_.empty())
        return Error{ErrorCode::parse_error, file.string() + ": the catalogue has a header but no objects"};
    return cat;
}

std::filesystem::path default_share_dir() {
    namespace fs = std::filesystem;
    if (const char* env = std::getenv("ROLLSENSE_SHARE"); env && *env) return env;
    // This library's own file: <prefix>/<libdir>/librollsense_data.so → <prefix>/share/rollsense.
    static const char anchor = 0;  // any object inside this library
    Dl_info info{};
    if (::dladdr(&anchor, &info) != 0 && info.dli_fname) {
        std::error_code ec;
        const fs::path installed = (fs::path(info.dli_fname).parent_path() / ROLLSENSE_LIB_TO_SHARE).lexically_normal();
        if (fs::exists(installed / "profiles", ec)) return installed;
    }
    return ROLLSENSE_SOURCE_SHARE_DIR;
}

}  // namespace rollsense
