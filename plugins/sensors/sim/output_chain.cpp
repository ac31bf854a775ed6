#include "output_chain.hpp"

#include <algorithm>
#include <cmath>

namespace rollsense::sim {

OutputChannel::OutputChannel(const OutputChainSettings& settings, double gain, double ambient_offset)
    : s_(settings), gain_(gain), ambient_(settings.ambient_kpa + ambient_offset) {}

double OutputChannel::quantise(double kpa_above_ambient) {
    const double p = std::min(kpa_above_ambient, s_.headroom_kpa);
    return std::round((ambient_ + p) / s_.count_kpa) * s_.count_kpa;
}

void OutputChannel::begin_trial(Rng rng, double start_time) {
    rng_ = rng;
    drift_rate_ = rng_.normal(0.0, s_.drift_sigma);
    start_time_ = start_time;
    double sum = 0.0;
    const int n = std::max(1, s_.baseline_samples);
    for (int i = 0; i < n; ++i) sum += quantise(rng_.normal(0.0, s_.noise_kpa));
    baseline_ = sum / n;
    lagged_ = 0.0;
    last_input_ = 0.0;
    last_time_ = start_time;
    primed_ = false;
}

double OutputChannel::sample(double time, double kpa) {
    const double input = gain_ * kpa;
    const double dt = time - last_time_;
    if (!primed_ || !(dt > 0.0) || !(s_.lag_tau > 0.0)) {
        // First sample (or no lag): the rubber has settled on the present load.
        lagged_ = primed_ && s_.lag_tau > 0.0 ? lagged_ : input;
    } else {
        // Exact response of a first-order lag to an input ramping linearly
        // from the previous sample to this one.
        if (dt != lag_dt_) {  // the period is constant: compute the decay once
            lag_dt_ = dt;
            lag_decay_ = std::exp(-dt / s_.lag_tau);
        }
        const double e = lag_decay_;
        const double slope = (input - last_input_) / dt;
        lagged_ = input - s_.lag_tau * slope + e * (lagged_ - last_input_ + s_.lag_tau * slope);
    }
    primed_ = true;
    last_input_ = input;
    last_time_ = time;
    const double drift = drift_rate_ * (time - start_time_);
    const double counts_kpa = quantise(lagged_ + drift + rng_.normal(0.0, s_.noise_kpa));
    return (counts_kpa - baseline_) / s_.kpa_per_unit;
}

}  // namespace rollsense::sim
