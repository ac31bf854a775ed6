#include "polygon_tumbling.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rollsense::sim {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxStep = 1.0 * kPi / 180.0;  // θ sub-step: a pivot spans tens of degrees
constexpr double kTouch = 1e-7;                 // mm: an edge this close to a finger touches it
}  // namespace

double PolygonTumbler::flat_orientation(int sides) { return -0.5 * kPi + kPi / sides; }

PolygonTumbler::PolygonTumbler(const HandGeometry& hand, PolygonShape shape, double centre_x, double psi0,
                               double theta0)
    : hand_(hand), shape_(std::move(shape)), psi_(psi0), theta_(theta0) {
    const int n = shape_.sides;
    shape_.radius.resize(static_cast<std::size_t>(n), shape_.radius.empty() ? 0.0 : shape_.radius.back());
    const double R = shape_.side / (2.0 * std::sin(kPi / n));
    for (int k = 0; k < n; ++k) {
        // A rounded edge is a circle tangent to both adjacent faces: its centre
        // sits r / sin(π/n) inside the sharp vertex.
        rho_.push_back(R - shape_.radius[static_cast<std::size_t>(k)] / std::sin(kPi / n));
        phase_.push_back(2.0 * kPi * k / n);
        cos_phase_.push_back(std::cos(phase_.back()));
        sin_phase_.push_back(std::sin(phase_.back()));
    }
    // Lowest and highest edges carry the load; ties go to the front / rear.
    choose_pivots(psi0, +1.0, 1e-9);
    anchor_pivots(centre_x, psi0, theta0);
}

// cos/sin of ψ are computed once per ψ and rotated by each vertex's fixed phase
// (the solver evaluates every vertex at the same ψ many times per sample).
void PolygonTumbler::set_trig(double psi) const {
    if (psi == trig_psi_) return;
    trig_psi_ = psi;
    trig_c_ = std::cos(psi);
    trig_s_ = std::sin(psi);
}
double PolygonTumbler::cx(int k, double psi) const {
    set_trig(psi);
    const auto i = static_cast<std::size_t>(k);
    return rho_[i] * (trig_c_ * cos_phase_[i] - trig_s_ * sin_phase_[i]);
}
double PolygonTumbler::cy(int k, double psi) const {
    set_trig(psi);
    const auto i = static_cast<std::size_t>(k);
    return rho_[i] * (trig_s_ * cos_phase_[i] + trig_c_ * sin_phase_[i]);
}
double PolygonTumbler::centre_y(double psi) const {
    return shape_.radius[static_cast<std::size_t>(a_)] - cy(a_, psi);
}
// The rounded edge A rolls on the sensing finger: its contact moves by −r_A·Δψ.
double PolygonTumbler::sensing_contact(double psi) const {
    return sa_star_ - shape_.radius[static_cast<std::size_t>(a_)] * (psi - psia_star_);
}
double PolygonTumbler::centre_x() const { return sensing_contact(psi_) - cx(a_, psi_); }
double PolygonTumbler::gap(double psi) const {
    return centre_y(psi) + cy(b_, psi) + shape_.radius[static_cast<std::size_t>(b_)];
}

// g(ψ, θ): pushing-finger coordinate of B's contact as the fingers put it, minus
// where B's rolling contact actually is on the pushing finger.
double PolygonTumbler::constraint(double psi, double tan_theta) const {
    const double xc = sensing_contact(psi) - cx(a_, psi);
    const double u_geometric = xc + cx(b_, psi) + hand_.array_distance -
                               (gap(psi) + hand_.finger_offset_sum) * tan_theta;
    const double u_rolling = ub_star_ + shape_.radius[static_cast<std::size_t>(b_)] * (psi - psib_star_);
    return u_geometric - u_rolling;
}

double PolygonTumbler::constraint_slope(double psi, double tan_theta) const {
    const auto A = static_cast<std::size_t>(a_), B = static_cast<std::size_t>(b_);
    // ρ·sin and ρ·cos of each pivot's angle are cy and cx.
    return -shape_.radius[A] + cy(a_, psi) - cy(b_, psi) - tan_theta * (cx(b_, psi) - cx(a_, psi)) - shape_.radius[B];
}

double PolygonTumbler::solve(double theta, double psi_guess) const {
    double psi = psi_guess;
    const double tan_theta = std::tan(theta);
    for (int it = 0; it < 30; ++it) {
        const double g = constraint(psi, tan_theta);
        if (std::abs(g) < 1e-11) break;  // mm: far below anything the rubber can feel
        const double slope = constraint_slope(psi, tan_theta);
        if (slope == 0.0) break;
        double step = g / slope;
        step = std::clamp(step, -0.2, 0.2);
        psi -= step;
        if (std::abs(step) < 1e-13) break;
    }
    return psi;
}

PolygonTumbler::Penetration PolygonTumbler::penetration(double psi, double theta) const {
    (void)theta;
    Penetration worst;
    const double yc = centre_y(psi);
    const double top = gap(psi);
    for (int k = 0; k < shape_.sides; ++k) {
        const double r = shape_.radius[static_cast<std::size_t>(k)];
        const double y = yc + cy(k, psi);
        if (k != a_ && -(y - r) > worst.depth) worst = {-(y - r), k, true};
        if (k != b_ && (y + r) - top > worst.depth) worst = {(y + r) - top, k, false};
    }
    return worst;
}

double PolygonTumbler::vertex_depth(int k, bool sensing, double psi, double theta) const {
    (void)theta;
    const double r = shape_.radius[static_cast<std::size_t>(k)];
    const double y = centre_y(psi) + cy(k, psi);
    return sensing ? -(y - r) : (y + r) - gap(psi);
}

void PolygonTumbler::choose_pivots(double psi, double direction, double tolerance) {
    // Sensing side: the lowest edge; among edges touching together, the one
    // ahead in the direction of travel (the prism tips over its leading edge).
    // Pushing side: the highest edge; among ties, the one behind.
    double lowest = 1e300, highest = -1e300;
    for (int k = 0; k < shape_.sides; ++k) {
        const double r = shape_.radius[static_cast<std::size_t>(k)];
        lowest = std::min(lowest, cy(k, psi) - r);
        highest = std::max(highest, cy(k, psi) + r);
    }
    int a = -1, b = -1;
    for (int k = 0; k < shape_.sides; ++k) {
        const double r = shape_.radius[static_cast<std::size_t>(k)];
        if (cy(k, psi) - r <= lowest + tolerance && (a < 0 || direction * (cx(k, psi) - cx(a, psi)) > 0)) a = k;
        if (cy(k, psi) + r >= highest - tolerance && (b < 0 || direction * (cx(k, psi) - cx(b, psi)) < 0)) b = k;
    }
    a_ = a;
    b_ = b;
}

// Make the pivots' contact anchors consistent with the object's present pose
// (centre at xc, orientation ψ, fingers at θ) without moving it: used at the
// start, at a landing and when a dwell ends.
void PolygonTumbler::anchor_pivots(double xc, double psi, double theta) {
    sa_star_ = xc + cx(a_, psi);
    psia_star_ = psi;
    ub_star_ = xc + cx(b_, psi) + hand_.array_distance - (gap(psi) + hand_.finger_offset_sum) * std::tan(theta);
    psib_star_ = psi;
}

void PolygonTumbler::land(double direction) {
    const double xc = centre_x();
    choose_pivots(psi_, direction, 1e-6);
    anchor_pivots(xc, psi_, theta_);
    ++landings_;
    // Tangential force needed to tip about the new pivots, over the normal force:
    // the two contact forces of a two-force body point along A→B.
    const double dx = std::abs((cx(b_, psi_)) - cx(a_, psi_));
    const double dy = gap(psi_);
    const double mu_tip = dy > 0.0 ? dx / dy : 0.0;
    if (landing_log_.size() < 64) landing_log_.push_back({theta_, sensing_contact(psi_), dy, mu_tip});
    double slip = 0.0;
    if (rng_ && slip_mean_ > 0.0) slip = rng_->uniform(0.0, 2.0 * slip_mean_);
    lock_needed_ = dwell_per_mu_ * mu_tip + slip;
    if (lock_needed_ > 0.0) {
        locked_ = true;
        lock_tan_ = std::tan(theta_);
        lock_width_ = dy + hand_.finger_offset_sum;
    }
}

void PolygonTumbler::advance(double theta) {
    for (int guard = 0; guard < 100000 && theta != theta_; ++guard) {
        const double direction = theta > theta_ ? 1.0 : -1.0;
        if (locked_) {
            // The landed face stays flat while the fingers slide past each other
            // by lock_needed_ (the hand's tangential compliance, then slip).
            const double slide = lock_width_ * (std::tan(theta) - lock_tan_);
            if (std::abs(slide) < lock_needed_) {
                theta_ = theta;
                return;
            }
            const double release = std::atan(lock_tan_ + direction * lock_needed_ / lock_width_);
            const double xc = centre_x();
            theta_ = release;
            locked_ = false;
            // The pushing finger slid over the prism: re-anchor B where it is now,
            // and tip over the edge that leads in the present direction.
            choose_pivots(psi_, direction, 1e-6);
            anchor_pivots(xc, psi_, theta_);
            continue;
        }
        const double step = std::clamp(theta - theta_, -kMaxStep, kMaxStep);
        const double theta_next = theta_ + step;
        const double psi_next = solve(theta_next, psi_);
        const Penetration p = penetration(psi_next, theta_next);
        if (p.depth <= kTouch) {
            theta_ = theta_next;
            psi_ = psi_next;
            continue;
        }
        // An edge reached a finger inside this step: find where. The depth of
        // that edge is smooth in θ, so false position (Illinois variant) gets
        // there in a few solves; the bracket keeps it safe.
        double lo = theta_, hi = theta_next, psi_lo = psi_;
        double f_lo = vertex_depth(p.vertex, p.sensing, psi_, theta_), f_hi = p.depth;
        int stale = 0;
        for (int it = 0; it < 60 && std::abs(hi - lo) > 1e-12; ++it) {
            double mid = f_hi != f_lo ? lo + (hi - lo) * (-f_lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
            if (!(mid > std::min(lo, hi) && mid < std::max(lo, hi))) mid = 0.5 * (lo + hi);
            const double psi_mid = solve(mid, psi_lo);
            const Penetration pm = penetration(psi_mid, mid);
            const double f_mid = vertex_depth(p.vertex, p.sensing, psi_mid, mid);
            if (pm.depth > kTouch * 0.5) {
                hi = mid;
                f_hi = f_mid;
                if (++stale >= 2) f_lo *= 0.5;
            } else {
                lo = mid;
                f_lo = f_mid;
                psi_lo = psi_mid;
                stale = 0;
                if (f_mid > -kTouch) break;  // touching within tolerance
            }
        }
        theta_ = lo;
        psi_ = psi_lo;
        land(direction);
    }
}

PolygonContact PolygonTumbler::contact() const {
    PolygonContact c;
    const double xc = centre_x();
    const double yc = centre_y(psi_);
    const int n = shape_.sides;
    c.contact = sensing_contact(psi_);
    // The faces next to the pivot, from the pivot's contact to the bottoms of the
    // neighbouring edges.
    for (int side : {-1, +1}) {
        const int k = (a_ + side + n) % n;
        const double r = shape_.radius[static_cast<std::size_t>(k)];
        const double dx = xc + cx(k, psi_) - c.contact;
        const double dy = std::max(0.0, yc + cy(k, psi_) - r);
        const double extent = std::max(std::abs(dx), 1e-3);
        if (dx >= 0.0) {
            c.slope_front = dy / extent;
            c.extent_front = extent;
        } else {
            c.slope_rear = dy / extent;
            c.extent_rear = extent;
        }
    }
    // A triangle's two neighbours can both lie on one side; keep a usable profile.
    if (c.extent_front == 0.0) c.extent_front = 1e-3, c.slope_front = 1e3;
    if (c.extent_rear == 0.0) c.extent_rear = 1e-3, c.slope_rear = 1e3;
    c.gap = gap(psi_);
    c.lever_arm = ub_star_ + shape_.radius[static_cast<std::size_t>(b_)] * (psi_ - psib_star_);
    c.dwelling = locked_;
    return c;
}

}  // namespace rollsense::sim
