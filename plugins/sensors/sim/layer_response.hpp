// What a barometer under the rubber layer reads for a given contact load
// (docs/simulation.md §2): the normal stress on the board is the contact load
// convolved with the layer's line-load response K.
//
// K is a Gaussian core (the bonded layer's near-hydrostatic bulge; its width is
// the main fitted parameter) plus a weak exponentially decaying tail (a bonded
// thin layer's far field decays exponentially with distance). The tail is a
// sech so that K stays smooth at the origin. K integrates to 1, so a load of
// F N/mm gives stresses that integrate to F: equilibrium.
//
// Every evaluation is closed form, which is what keeps a frame below 2 µs.
#pragma once

namespace rollsense::sim {

class LayerKernel {
public:
    LayerKernel() = default;
    // fwhm: full width at half maximum of the core, mm; tail_at_pitch: tail
    // value at distance `pitch` as a fraction of K(0); tail_length: decay length, mm.
    LayerKernel(double fwhm, double tail_at_pitch, double pitch, double tail_length);

    // Response at distance u to a unit line load (1/mm).
    double line(double u) const;
    // Response at distance u to a unit load spread as a Gaussian of variance
    // `spread_var` (mm²) around the origin: the core widens, the tail is broad
    // enough to be taken at the centre.
    double spread(double u, double spread_var) const;
    // Response at x to a pressure distribution that is linear from p0 at u0 to p1
    // at u1 (u1 > u0; pressures in N/mm² give a stress in N/mm²).
    double linear_segment(double x, double u0, double u1, double p0, double p1) const;
    // Response at x to a continuous piecewise-linear pressure over three nodes
    // u0 <= u1 <= u2 (pressures q0, q1, q2): the two faces beside a pivot. Same
    // result as two linear_segment calls, with the shared node evaluated once.
    double two_segments(double x, double u0, double u1, double u2, double q0, double q1, double q2) const;

    double sigma() const { return sigma_; }
    double fwhm() const { return fwhm_; }
    double tail_weight() const { return tail_weight_; }
    double peak() const { return line(0.0); }

private:
    double fwhm_ = 4.5;
    double sigma_ = 4.5 / 2.3548200450309493;
    double tail_weight_ = 0.0;   // fraction of the load carried by the tail
    double tail_length_ = 4.0;
};

// Hertz line contact of a rigid cylinder on the rubber: semi-elliptic pressure of
// half-width b = sqrt(4 F R / (pi E*)). Its variance is b²/4, which is what
// LayerKernel::spread needs (the moment-matched Gaussian differs from the exact
// convolution by well under 1 % for b < sigma).
double hertz_half_width(double line_load, double radius, double contact_modulus);

}  // namespace rollsense::sim
