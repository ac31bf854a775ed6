// A regular polygonal prism tumbling between the parallel fingers
// (docs/simulation.md §1).
//
// The prism pivots on one lateral edge against each finger: edge A on the
// sensing finger, edge B on the pushing finger. Each edge is rounded (radius
// r_k), so a pivoting edge rolls by r_k·Δψ instead of staying at a point. With
// both contacts rolling without slip, the orientation ψ follows from one
// scalar constraint g(ψ, θ) = 0 (the pushing contact keeps its place on the
// pushing finger while the palm keeps the fingers parallel), solved by Newton
// from the previous orientation. When another edge touches a finger (found by
// bisection in θ), it becomes the pivot: the sensing contact jumps forward by
// about one edge length.
//
// A landing face does not tip over at once: tipping needs the tangential force
// to reach μ_tip·F (μ_tip = horizontal over normal distance between the new
// pivots: 1 for a square, 0.58 for a hexagon, 0.33 for a pentagon), which the
// hand's tangential compliance builds up while the fingers slide past each
// other by `dwell_per_mu · μ_tip` (plus a little slip). During that dwell the
// face stays flat and loads the rubber under its whole length.
#pragma once

#include <vector>

#include "kinematics.hpp"
#include "rng.hpp"

namespace rollsense::sim {

struct PolygonShape {
    int sides = 4;
    double side = 13.0;          // a, mm
    std::vector<double> radius;  // per lateral edge (vertex of the base), mm
};

// What the rubber sees under the sensing pivot, and the pushing lever arm.
struct PolygonContact {
    double contact = 0.0;  // x of the pivot on the sensing finger, mm
    double slope_rear = 0.0, slope_front = 0.0;
    double extent_rear = 0.0, extent_front = 0.0;
    double lever_arm = 0.0;  // pushing contact from the pushing joint, mm
    double gap = 0.0;        // distance between the finger surfaces, mm
    bool dwelling = false;   // a landed face is still flat
};

// One landing: an edge reached a finger and became a pivot.
struct Landing {
    double theta = 0.0;    // rad
    double contact = 0.0;  // sensing pivot's contact after the landing, mm
    double gap = 0.0;      // finger gap at the landing, mm
    double mu_tip = 0.0;   // friction needed to tip over the new pivots
};

class PolygonTumbler {
public:
    PolygonTumbler() = default;
    // Place the prism with its centre at x = centre_x, orientation psi0 (rad;
    // psi0 = flat_orientation() puts a face flat on the sensing finger) and
    // fingers at theta0 (rad).
    PolygonTumbler(const HandGeometry& hand, PolygonShape shape, double centre_x, double psi0, double theta0);

    // ψ at which a face lies flat on the sensing finger, edge 0 at its front.
    static double flat_orientation(int sides);

    // Relative finger slide (mm) a landing face dwells per unit μ_tip, and the
    // slip drawn per landing (uniform in [0, 2·slip_mean]).
    void set_dwell(double dwell_per_mu, double slip_mean, Rng* rng) {
        dwell_per_mu_ = dwell_per_mu;
        slip_mean_ = slip_mean;
        rng_ = rng;
    }

    // Move the fingers to theta (either direction) and follow the prism.
    void advance(double theta);

    PolygonContact contact() const;
    double orientation() const { return psi_; }
    double theta() const { return theta_; }
    int sensing_pivot() const { return a_; }
    int pushing_pivot() const { return b_; }
    int landings() const { return landings_; }
    // The first landings of the roll (kept for tests and diagnostics; at most 64).
    const std::vector<Landing>& landing_log() const { return landing_log_; }
    double centre_x() const;
    double centre_y() const { return centre_y(psi_); }
    // Deepest penetration of a non-pivot edge into either finger (mm, <= ~0 when consistent).
    double max_penetration() const { return penetration(psi_, theta_).depth; }

private:
    struct Penetration {
        double depth = -1e300;
        int vertex = -1;
        bool sensing = true;
    };
    double cx(int k, double psi) const;
    double cy(int k, double psi) const;
    double centre_y(double psi) const;
    double sensing_contact(double psi) const;
    double gap(double psi) const;
    void set_trig(double psi) const;
    double constraint(double psi, double tan_theta) const;
    double constraint_slope(double psi, double tan_theta) const;
    double vertex_depth(int k, bool sensing, double psi, double theta) const;
    double solve(double theta, double psi_guess) const;
    Penetration penetration(double psi, double theta) const;
    void choose_pivots(double psi, double direction, double tolerance);
    void anchor_pivots(double xc, double psi, double theta);
    void land(double direction);

    HandGeometry hand_;
    PolygonShape shape_;
    std::vector<double> rho_, phase_, cos_phase_, sin_phase_;
    mutable double trig_psi_ = 1e300, trig_c_ = 1.0, trig_s_ = 0.0;
    double psi_ = 0.0, theta_ = 0.0;
    int a_ = 0, b_ = 0;
    double sa_star_ = 0.0, psia_star_ = 0.0;  // sensing contact x when pivot A started
    double ub_star_ = 0.0, psib_star_ = 0.0;  // pushing contact coordinate when B started
    bool locked_ = false;
    double lock_tan_ = 0.0, lock_width_ = 0.0, lock_needed_ = 0.0;
    double dwell_per_mu_ = 0.0, slip_mean_ = 0.0;
    Rng* rng_ = nullptr;
    int landings_ = 0;
    std::vector<Landing> landing_log_;
};

}  // namespace rollsense::sim
