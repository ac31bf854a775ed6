#include "layer_response.hpp"

#include <cmath>

namespace rollsense::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInvSqrt2Pi = 0.39894228040143267794;
constexpr double kFwhmPerSigma = 2.3548200450309493;  // 2 sqrt(2 ln 2)

double phi(double z) { return kInvSqrt2Pi * std::exp(-0.5 * z * z); }
double Phi(double z) { return 0.5 * std::erfc(-z * 0.70710678118654752440); }
double sech(double x) {
    const double e = std::exp(-std::abs(x));
    return 2.0 * e / (1.0 + e * e);
}

// Gudermannian: ∫₀ᵗ sech = 2 atan(eᵗ) − π/2 (one exp, one atan).
double gd(double t) {
    if (t > 40.0) return 0.5 * kPi;
    if (t < -40.0) return -0.5 * kPi;
    return 2.0 * std::atan(std::exp(t)) - 0.5 * kPi;
}

}  // namespace

LayerKernel::LayerKernel(double fwhm, double tail_at_pitch, double pitch, double tail_length)
    : fwhm_(fwhm), sigma_(fwhm / kFwhmPerSigma), tail_length_(tail_length) {
    // Choose the tail's share w so that tail(pitch) = tail_at_pitch * K(0):
    // K(0) = (1-w) c + w e, tail(pitch) = w e sech(pitch/λ), solved for w.
    const double c = kInvSqrt2Pi / sigma_;
    const double e = 1.0 / (kPi * tail_length_);
    const double r = tail_at_pitch;
    const double denominator = e * sech(pitch / tail_length_) - r * e + r * c;
    tail_weight_ = r > 0.0 && denominator > 0.0 ? r * c / denominator : 0.0;
    if (tail_weight_ > 0.9) tail_weight_ = 0.9;
}

double LayerKernel::line(double u) const {
    return (1.0 - tail_weight_) * phi(u / sigma_) / sigma_ +
           tail_weight_ * sech(u / tail_length_) / (kPi * tail_length_);
}

double LayerKernel::spread(double u, double spread_var) const {
    const double s = std::sqrt(sigma_ * sigma_ + spread_var);
    return (1.0 - tail_weight_) * phi(u / s) / s + tail_weight_ * sech(u / tail_length_) / (kPi * tail_length_);
}

double LayerKernel::linear_segment(double x, double u0, double u1, double p0, double p1) const {
    const double length = u1 - u0;
    if (!(length > 0.0)) return 0.0;
    // Core: ∫ (A + Bξ) φ((ξ-x)/σ)/σ dξ with z = (ξ-x)/σ.
    const double B = (p1 - p0) / length;
    const double A = p0 - B * u0;
    const double z0 = (u0 - x) / sigma_;
    const double z1 = (u1 - x) / sigma_;
    const double core = (A + B * x) * (Phi(z1) - Phi(z0)) + B * sigma_ * (phi(z0) - phi(z1));
    // Tail: exact for the segment's mean pressure (∫ sech = gd, the Gudermannian);
    // the tail is broad, so the linear variation within a segment hardly matters.
    const double mean_p = 0.5 * (p0 + p1);
    const double tail = mean_p * (gd((x - u0) / tail_length_) - gd((x - u1) / tail_length_)) / kPi;
    return (1.0 - tail_weight_) * core + tail_weight_ * tail;
}

double LayerKernel::two_segments(double x, double u0, double u1, double u2, double q0, double q1,
                                 double q2) const {
    const double z[3] = {(u0 - x) / sigma_, (u1 - x) / sigma_, (u2 - x) / sigma_};
    const double u[3] = {u0, u1, u2}, q[3] = {q0, q1, q2};
    double Phi_z[3], phi_z[3], gd_z[3];
    for (int i = 0; i < 3; ++i) {
        Phi_z[i] = Phi(z[i]);
        phi_z[i] = phi(z[i]);
        gd_z[i] = gd((x - u[i]) / tail_length_);
    }
    double core = 0.0, tail = 0.0;
    for (int i = 0; i < 2; ++i) {
        const double length = u[i + 1] - u[i];
        if (!(length > 0.0)) continue;
        const double B = (q[i + 1] - q[i]) / length;
        const double A = q[i] - B * u[i];
        core += (A + B * x) * (Phi_z[i + 1] - Phi_z[i]) + B * sigma_ * (phi_z[i] - phi_z[i + 1]);
        tail += 0.5 * (q[i] + q[i + 1]) * (gd_z[i] - gd_z[i + 1]) / kPi;
    }
    return (1.0 - tail_weight_) * core + tail_weight_ * tail;
}

double hertz_half_width(double line_load, double radius, double contact_modulus) {
    if (!(line_load > 0.0) || !(contact_modulus > 0.0)) return 0.0;
    return std::sqrt(4.0 * line_load * radius / (kPi * contact_modulus));
}

}  // namespace rollsense::sim
