// The MPL115A output chain of one barometer (docs/simulation.md §3):
//
//   stress on the board (kPa) ─▶ viscoelastic lag ─▶ + drift + noise ─▶ saturate
//     ─▶ quantise to the chip's counts ─▶ scale to the paper's unitless reading
//     ─▶ subtract the baseline taken before the object was clamped
//
// The noise is added before the quantiser because that is where it arises
// (the ADC quantises its own input noise); with σ below one count the output
// then flickers between neighbouring counts as the real chip's does.
#pragma once

#include "rng.hpp"

namespace rollsense::sim {

struct OutputChainSettings {
    double lag_tau = 0.04;          // s, rubber's first-order viscoelastic lag
    // kPa per output count: the MPL115A's 10-bit Pcomp spans 50-115 kPa,
    // (115 − 50) / 1023 kPa per count (datasheet transfer function).
    double count_kpa = 65.0 / 1023.0;
    double kpa_per_unit = 16.0;     // kPa per unit of the paper's reading
    // σ of the white noise, kPa: no datasheet figure; sized by the paper's noise
    // after smoothing (p99 of |noise| ≤ 0.005, none at 0.01: bench/sim).
    double noise_kpa = 0.03;
    double drift_sigma = 0.0;       // σ of the per-trial linear drift rate, kPa/s (no source: off)
    double headroom_kpa = 13.0;     // saturation above ambient, kPa
    double ambient_kpa = 101.325;   // ambient pressure (sets the quantiser's phase)
    int baseline_samples = 16;      // readings averaged for the baseline
};

class OutputChannel {
public:
    OutputChannel() = default;
    // gain: per-device gain of this barometer; ambient_offset: its offset from the
    // nominal ambient (kPa), which shifts where the count boundaries fall.
    OutputChannel(const OutputChainSettings& settings, double gain, double ambient_offset);

    // New trial: noise stream, drift rate, and the baseline (taken while the
    // hand is open, so it contains no contact load).
    void begin_trial(Rng rng, double start_time);
    // Reading (units) at time t for the stress `kpa` on the board at that time.
    double sample(double time, double kpa);

private:
    double quantise(double kpa_above_ambient);

    OutputChainSettings s_;
    double gain_ = 1.0;
    double ambient_ = 101.325;
    Rng rng_;
    double drift_rate_ = 0.0;
    double start_time_ = 0.0;
    double baseline_ = 0.0;
    double lagged_ = 0.0;
    double last_input_ = 0.0;
    double last_time_ = 0.0;
    bool primed_ = false;
    double lag_dt_ = -1.0, lag_decay_ = 0.0;
};

}  // namespace rollsense::sim
