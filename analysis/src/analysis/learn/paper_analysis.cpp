#include "analysis/learn/paper_analysis.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "rollsense/log.hpp"

namespace rollsense::learn {

std::vector<ObjectShape> object_shapes(const ObjectCatalogue& catalogue) {
    std::vector<ObjectShape> out;
    out.reserve(catalogue.objects().size());
    for (const auto& o : catalogue.objects()) out.push_back({o.id, o.base, o.is_cylinder() ? 0.0 : o.side});
    return out;
}

const std::vector<ObjectShape>& paper_objects() {
    static const std::vector<ObjectShape> objects = [] {
        const auto file = default_share_dir() / kStockCatalogue;
        auto loaded = ObjectCatalogue::load(file);
        if (!loaded) {
            log_error("analysis", loaded.error().message +
                                      " (the analyses read the object shapes from it; set ROLLSENSE_SHARE to the "
                                      "share folder that holds objects/)");
            return std::vector<ObjectShape>{};
        }
        return object_shapes(loaded.value());
    }();
    return objects;
}

const PaperAnalysis& paper_figures() {
    static const PaperAnalysis p = [] {
        PaperAnalysis a;
        a.clean = {1164, 1350};
        a.cylinders_clean = {450, 450};
        a.polygons_clean = {714, 900};
        a.accuracy = {1053, 1164};  // 90.5 % of 1,164 (the paper gives the percentage)
        a.family_correct = {0, 0};  // "almost perfectly separated": no count published
        a.cylinders_misclassified = {7, 450};
        a.polygon_edge_correct = {679, 714};
        a.hexagons_misclassified = {45, 0};  // the paper does not give the clean hexagon count
        a.hexagons_called_pentagons = {33, 45};
        a.pentagons_misclassified = {47, 0};
        a.pentagons_called_hexagons = {31, 47};
        return a;
    }();
    return p;
}

PaperAnalysis analyse_like_paper(const std::vector<features::FeatureRow>& rows,
                                 std::span<const std::size_t> table_rows, std::span<const int> truth,
                                 std::span<const int> predicted, const std::vector<std::string>& class_names,
                                 const std::vector<ObjectShape>& catalogue) {
    std::map<std::string, const ObjectShape*> shape;
    for (const auto& o : catalogue) shape[o.id] = &o;
    std::set<std::string> unknown;
    PaperAnalysis a;
    for (const auto& r : rows) {
        ++a.clean.n;
        a.clean.k += r.clean;
        auto it = shape.find(r.object);
        if (it == shape.end()) {
            unknown.insert(r.object);
            continue;
        }
        Count& c = it->second->cylinder() ? a.cylinders_clean : a.polygons_clean;
        ++c.n;
        c.k += r.clean;
    }
    for (std::size_t i = 0; i < table_rows.size() && i < predicted.size(); ++i) {
        const std::string& t_name = class_names[static_cast<std::size_t>(truth[i])];
        const std::string& p_name = class_names[static_cast<std::size_t>(predicted[i])];
        ++a.accuracy.n;
        a.accuracy.k += truth[i] == predicted[i];
        auto ti = shape.find(t_name), pi = shape.find(p_name);
        if (ti == shape.end() || pi == shape.end()) continue;
        const ObjectShape& t = *ti->second;
        const ObjectShape& p = *pi->second;
        const bool wrong = truth[i] != predicted[i];
        ++a.family_correct.n;
        a.family_correct.k += t.cylinder() == p.cylinder();
        if (t.cylinder()) {
            ++a.cylinders_misclassified.n;
            a.cylinders_misclassified.k += wrong;
        } else {
            ++a.polygon_edge_correct.n;
            a.polygon_edge_correct.k += !p.cylinder() && p.side_mm == t.side_mm;
        }
        if (t.base == "hexagon") {
            ++a.hexagons_misclassified.n;
            if (wrong) {
                ++a.hexagons_misclassified.k;
                ++a.hexagons_called_pentagons.n;
                a.hexagons_called_pentagons.k += p.base == "pentagon";
            }
        }
        if (t.base == "pentagon") {
            ++a.pentagons_misclassified.n;
            if (wrong) {
                ++a.pentagons_misclassified.k;
                ++a.pentagons_called_hexagons.n;
                a.pentagons_called_hexagons.k += p.base == "hexagon";
            }
        }
    }
    a.unknown_objects.assign(unknown.begin(), unknown.end());
    return a;
}

namespace {

std::string cell(const Count& c, bool has_k = true) {
    char buf[64];
    if (!has_k) return "-";
    if (c.n == 0 && c.k == 0) return "n/a";  // nothing to count: no such trials (or no figure in the paper)
    if (c.n == 0) std::snprintf(buf, sizeof buf, "%zu", c.k);
    else std::snprintf(buf, sizeof buf, "%zu / %zu (%.1f %%)", c.k, c.n, 100.0 * c.fraction());
    return buf;
}

}  // namespace

std::string format_paper_comparison(const PaperAnalysis& ours) {
    const PaperAnalysis& paper = paper_figures();
    struct Line {
        const char* label;
        const Count PaperAnalysis::*field;
    };
    const Line lines[] = {
        {"clean trials / collected", &PaperAnalysis::clean},
        {"cylinder trials clean", &PaperAnalysis::cylinders_clean},
        {"polygon trials clean", &PaperAnalysis::polygons_clean},
        {"accuracy (correct / evaluated trials)", &PaperAnalysis::accuracy},  // the clean ones, unless --trials all
        {"cylinder vs polygon correct", &PaperAnalysis::family_correct},
        {"cylinders misclassified", &PaperAnalysis::cylinders_misclassified},
        {"polygons, correct base edge length", &PaperAnalysis::polygon_edge_correct},
        {"hexagons misclassified", &PaperAnalysis::hexagons_misclassified},
        {"  of those called pentagons", &PaperAnalysis::hexagons_called_pentagons},
        {"pentagons misclassified", &PaperAnalysis::pentagons_misclassified},
        {"  of those called hexagons", &PaperAnalysis::pentagons_called_hexagons},
    };
    std::string out;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%-38s %-26s %s\n", "figure", "this data", "paper");
    out += buf;
    for (const auto& l : lines) {
        const bool paper_has = !(l.field == &PaperAnalysis::family_correct);
        std::string paper_cell = paper_has ? cell(paper.*l.field) : "almost perfectly separated";
        std::snprintf(buf, sizeof buf, "%-38s %-26s %s\n", l.label, cell(ours.*l.field).c_str(), paper_cell.c_str());
        out += buf;
    }
    if (!ours.unknown_objects.empty()) {
        out += "objects not in the catalogue (left out of the shape rows):";
        for (const auto& u : ours.unknown_objects) out += " " + u;
        out += "\n";
    }
    return out;
}

}  // namespace rollsense::learn
