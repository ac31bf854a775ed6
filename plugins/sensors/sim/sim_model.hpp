// The whole physical model of one simulated trial, independent of the plugin
// interface (so tests and the calibration bench drive it directly).
//
//   finger angle θ ─▶ kinematics (cylinder roll / polygon tumble) ─▶ contact load
//     ─▶ layer response at each barometer ─▶ output chain ─▶ ch1..ch3
//
// Every number here is a named setting; sim_schema.cpp documents each one with
// its unit, and docs/simulation.md says which were fitted and how.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "contact_load.hpp"
#include "kinematics.hpp"
#include "layer_response.hpp"
#include "rollsense/object_catalogue.hpp"
#include "output_chain.hpp"
#include "polygon_tumbling.hpp"
#include "rng.hpp"

namespace rollsense::sim {

// The objects come from the data layer's catalogue (share/objects/*.csv).
using rollsense::ObjectCatalogue;
using rollsense::ObjectSpec;

inline constexpr int kChannels = 3;

struct SimParameters {
    HandGeometry hand;
    double sensor_pitch = 8.0;             // mm between barometer centres
    double sensor_position_jitter = 0.3;   // mm, per device
    double kernel_fwhm = 4.5;              // mm, layer response core
    double kernel_fwhm_jitter = 0.10;      // relative, per device
    double kernel_tail_at_pitch = 0.015;   // tail / peak at one pitch
    double kernel_tail_length = 4.0;       // mm
    double contact_modulus = 0.3;          // MPa, E* for the Hertz contact of a cylinder
    double foundation_stiffness = 0.05;    // N/mm³, rubber as an elastic foundation under an edge
    double clamp_line_load = 0.03;         // N/mm, median clamping load at the reference lever arm
    // mA: the current clamp_line_load is calibrated at (share/lua/etroll.lua's
    // clamp_current); the load scales with current / this. 0: current only gates.
    double clamp_reference_current = 120.0;
    double clamp_current_threshold = 5.0;  // mA; below: not clamped
    double force_log_sigma = 0.17;         // per-trial log-normal spread of the clamping load
    double palm_oscillation = 0.06;        // relative force modulation at the reference speed
    double palm_reference_speed = 13.74;   // deg/s (profile velocity 10)
    double palm_frequency_min = 1.0;       // Hz
    double palm_frequency_max = 3.0;       // Hz
    double start_centre = -27.5;          // mm, mean start position of the object's centre
    double start_range = 20.0;             // mm, width of the uniform start distribution
    double start_tilt = 1.0;               // deg, σ of a polygon's tilt off face-flat
    double cylinder_slip_max = 0.04;       // slip fraction, uniform in [0, max]
    double polygon_slip = 0.3;             // mm, mean slip per landing
    double face_dwell = 4.0;               // mm of finger slide per unit μ_tip a landed face stays flat
    // The paper's protocol: one printed specimen per object, mounted on the
    // winch string once for its 150 rolls (docs/simulation.md "Protocol").
    double specimen_size_tolerance = 0.2;  // mm, uniform ± on a specimen's diameter (cylinder) or edge (prism)
    bool specimen_edges = true;            // edge radii drawn once per specimen (false: per trial)
    double mount_start_sigma = 0.0;        // mm, σ of a mounting's shift of the start position
    double mount_force_log_sigma = 0.0;    // σ_ln of a mounting's clamping-load factor
    double mount_force_trend = 0.0;        // relative clamping-load change per 100 rolls of a mounting
    double gain_jitter = 0.10;             // relative, per device (uniform ±)
    double ambient_offset_range = 0.15;    // kPa, per device (uniform ±): quantiser phase
    OutputChainSettings chain;
    std::uint64_t device_seed = 1;
};

// Fixed per-device randomness: where the barometers really are, how wide each
// one's response is, its gain.
struct DeviceState {
    std::array<double, kChannels> sensor_x{};
    std::array<LayerKernel, kChannels> kernel{};
    std::array<double, kChannels> gain{};
    std::array<double, kChannels> ambient_offset{};
};
DeviceState make_device(const SimParameters& p);

// One trial's draws, exposed for tests and the bench.
struct TrialDraws {
    double start_centre = 0.0;  // mm
    double tilt = 0.0;          // rad
    double force_factor = 1.0;
    double palm_frequency = 2.0, palm_phase = 0.0;
    double cylinder_slip = 0.0;
    std::vector<double> edge_radius;
};

// Where a trial sits in the protocol: which mounting of its specimen (a name
// unique in the run; empty = none recorded, no mount effects) and how many
// rolls of that mounting came before it.
struct MountPosition {
    std::string mount;
    long index = 0;
};

// The specimen of a catalogue object for a device seed: its printed size
// within specimen_size_tolerance. A pure function of (device seed, object).
ObjectSpec make_specimen(const SimParameters& p, const ObjectSpec& nominal);

class TrialModel {
public:
    // `object` may be null: no object between the fingers (readings are noise).
    // Every draw is a pure function of (device seed, object, mount, index in
    // mount, trial seed), never of the order trials are recorded in.
    TrialModel(const SimParameters& params, const DeviceState& device, const ObjectSpec* object,
               std::uint64_t trial_seed, const MountPosition& mount = {});
    TrialModel(const TrialModel&) = delete;  // object_ may point into specimen_
    TrialModel& operator=(const TrialModel&) = delete;

    // Recording starts with the fingers at theta (rad) at `time` (s). The
    // first of a trial places the object; a later one keeps it where it is.
    void start(double time, double theta);
    // One sample: the sensing finger at theta (rad), clamping current (mA).
    std::array<double, kChannels> sample(double time, double theta, double clamp_current);
    // The contact stress (kPa) at each barometer for the present pose, before the output chain.
    const std::array<double, kChannels>& last_stress() const { return stress_; }

    const TrialDraws& draws() const { return draws_; }
    bool started() const { return started_; }
    // Present contact position on the sensing finger (mm) and clamping load (N/mm).
    double contact_position() const { return contact_; }
    double line_load() const { return line_load_; }
    const PolygonTumbler* tumbler() const { return polygon_ ? &*polygon_ : nullptr; }

private:
    void compute_stress(double time, double theta, double clamp_current);

    SimParameters p_;
    const DeviceState* device_;
    std::optional<ObjectSpec> specimen_;
    const ObjectSpec* object_;
    std::uint64_t seed_;
    TrialDraws draws_;
    Rng slip_rng_;
    std::array<OutputChannel, kChannels> channels_{};
    std::optional<CylinderRoll> cylinder_;
    std::optional<PolygonTumbler> polygon_;
    std::array<double, kChannels> stress_{};
    bool started_ = false;
    int recordings_ = 0;  // recordings started in this trial (the object is placed at the first)
    double start_time_ = 0.0;  // recording start: times inside a trial are relative to it (resume-identical)
    double last_theta_ = 0.0, last_time_ = 0.0, speed_ = 0.0;  // speed in rad/s, low-passed
    double contact_ = 0.0, line_load_ = 0.0, line_load_prev_ = 0.0;
};

}  // namespace rollsense::sim
