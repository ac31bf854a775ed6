#include "contact_load.hpp"

#include <algorithm>
#include <cmath>

namespace rollsense::sim {

namespace {

// Force (per unit k) one side carries at depth δ: a triangle δ²/(2t) until the
// pressure reaches the face's end (δ = t ℓ), then a trapezoid ℓ (δ − t ℓ / 2).
double side_force(double depth, double slope, double extent) {
    if (depth <= 0.0) return 0.0;
    if (slope * extent > depth) return depth * depth / (2.0 * slope);
    return extent * (depth - 0.5 * slope * extent);
}

PressureSegment side_segment(double depth, double slope, double extent, double stiffness, double contact,
                             bool front) {
    const double reach = slope * extent > depth ? depth / slope : extent;
    const double p_pivot = stiffness * depth;
    const double p_end = stiffness * std::max(0.0, depth - slope * reach);
    PressureSegment s;
    if (front) {
        s.u0 = contact;
        s.u1 = contact + reach;
        s.p0 = p_pivot;
        s.p1 = p_end;
    } else {
        s.u0 = contact - reach;
        s.u1 = contact;
        s.p0 = p_end;
        s.p1 = p_pivot;
    }
    return s;
}

}  // namespace

PivotLoad winkler_pivot_load(const PivotProfile& pr, double line_load, double stiffness) {
    PivotLoad out;
    if (!(line_load > 0.0) || !(stiffness > 0.0)) {
        out.segments[0] = out.segments[1] = PressureSegment{pr.contact, pr.contact, 0.0, 0.0};
        return out;
    }
    const double target = line_load / stiffness;  // mm²
    const double tr = std::max(pr.slope_rear, 0.0), tf = std::max(pr.slope_front, 0.0);
    const double lr = std::max(pr.extent_rear, 1e-6), lf = std::max(pr.extent_front, 1e-6);
    auto total = [&](double d) { return side_force(d, tr, lr) + side_force(d, tf, lf); };

    // The total is increasing and piecewise quadratic in δ with breakpoints at
    // t ℓ of each side: find the piece that holds the target, then solve it exactly.
    double lo = 0.0;
    double breaks[2] = {tr * lr, tf * lf};
    if (breaks[0] > breaks[1]) std::swap(breaks[0], breaks[1]);
    double hi = 0.0;
    for (double b : breaks) {
        if (b > lo && total(b) >= target) {
            hi = b;
            break;
        }
        if (b > lo) lo = b;
    }
    double depth;
    {
        // On (lo, hi) each side is either a triangle (a δ²) or a trapezoid (ℓ δ − c):
        // collect a δ² + b δ + c = target.
        const double probe = hi > lo ? 0.5 * (lo + hi) : lo + 1.0;
        double qa = 0.0, qb = 0.0, qc = 0.0;
        for (int side = 0; side < 2; ++side) {
            const double t = side == 0 ? tr : tf, l = side == 0 ? lr : lf;
            if (t * l > probe) {
                qa += 1.0 / (2.0 * t);
            } else {
                qb += l;
                qc -= 0.5 * t * l * l;
            }
        }
        qc -= target;
        if (qa > 0.0) {
            depth = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
        } else {
            depth = -qc / qb;
        }
    }
    out.depth = depth;
    out.segments[0] = side_segment(depth, tr, lr, stiffness, pr.contact, false);
    out.segments[1] = side_segment(depth, tf, lf, stiffness, pr.contact, true);
    return out;
}

}  // namespace rollsense::sim
