#include "sim_schema.hpp"

#include <algorithm>

namespace rollsense::sim {

ParamSchema sim_schema() {
    const SimParameters d;  // defaults live in one place: SimParameters
    const OutputChainSettings c;
    ParamSchema schema{
        param_string("catalogue", std::string(kStockCatalogue),
                     "object catalogue CSV, relative to the share folder unless absolute"),
        param_string("sensing_joint", std::string("sensing_finger"),
                     "actuator joint whose angle (deg) rolls the object across the array"),
        param_string("pushing_joint", std::string("pushing_finger"),
                     "actuator joint whose current (mA) clamps the object; ~0 means not clamped"),
        param_string("palm_joint", std::string("palm"),
                     "actuator joint giving the palm width (mm); reported by the 'state' operation"),
        param_int("device_seed", 1, "seed of the fixed per-device randomness (gains, positions, widths)", 0),
        // (the hand geometry goes here: inserted below from its one home)
        param_number("sensor_pitch", d.sensor_pitch, "distance between barometer centres", 1.0, 50.0, "mm"),
        param_number("sensor_position_jitter", d.sensor_position_jitter,
                     "per-device error of each barometer's position (uniform +-)", 0.0, 5.0, "mm"),
        // Rubber layer
        param_number("kernel_fwhm", d.kernel_fwhm,
                     "FWHM of the layer's line-load response core (fitted; plausible 3.5-7)", 1.0, 20.0, "mm"),
        param_number("kernel_fwhm_jitter", d.kernel_fwhm_jitter,
                     "per-device relative spread of each barometer's response width (uniform +-)", 0.0, 0.5, "1"),
        param_number("kernel_tail_at_pitch", d.kernel_tail_at_pitch,
                     "layer response tail one pitch away, as a fraction of its peak", 0.0, 0.5, "1"),
        param_number("kernel_tail_length", d.kernel_tail_length, "decay length of the response tail", 0.1, 50.0,
                     "mm"),
        param_number("contact_modulus", d.contact_modulus,
                     "E* of the rubber for a cylinder's Hertz line contact", 0.01, 100.0, "MPa"),
        param_number("foundation_stiffness", d.foundation_stiffness,
                     "rubber as an elastic foundation under a prism's edge or face", 0.001, 100.0, "N/mm^3"),
        // Clamping
        param_number("clamp_line_load", d.clamp_line_load,
                     "median clamping load per unit prism length at the reference lever arm", 0.0, 10.0, "N/mm"),
        param_number("clamp_reference_current", d.clamp_reference_current,
                     "the pushing current clamp_line_load is calibrated at (etroll.lua's clamp_current): the load "
                     "scales with current / this; 0: current only gates clamping", 0.0,
                     10000.0, "mA"),
        param_number("clamp_current_threshold", d.clamp_current_threshold,
                     "pushing-finger current below which the object counts as not clamped", 0.0, 10000.0, "mA"),
        param_number("force_log_sigma", d.force_log_sigma, "per-trial log-normal spread of the clamping load",
                     0.0, 2.0, "1"),
        param_number("palm_oscillation", d.palm_oscillation,
                     "palm-controller force modulation at the reference speed (scales as 1/speed)", 0.0, 1.0, "1"),
        param_number("palm_reference_speed", d.palm_reference_speed,
                     "finger speed at which the modulation equals palm_oscillation", 0.1, 1000.0, "deg/s"),
        param_number("palm_frequency_min", d.palm_frequency_min, "lowest palm oscillation frequency", 0.0, 50.0,
                     "Hz"),
        param_number("palm_frequency_max", d.palm_frequency_max, "highest palm oscillation frequency", 0.0, 50.0,
                     "Hz"),
        // Per-trial placement and motion
        param_number("start_centre", d.start_centre,
                     "mean start position of the object's centre, from barometer 2 (fitted)", -200.0, 200.0, "mm"),
        param_number("start_range", d.start_range, "width of the uniform start-position spread", 0.0, 200.0, "mm"),
        param_number("start_tilt", d.start_tilt, "sigma of a prism's tilt off face-flat at the start", 0.0, 45.0,
                     "deg"),
        param_number("cylinder_slip_max", d.cylinder_slip_max,
                     "a cylinder's slip: fraction of contact travel lost, uniform in [0, max]", 0.0, 0.5, "1"),
        param_number("polygon_slip", d.polygon_slip, "mean slip of a prism per landing (uniform in [0, 2x])", 0.0,
                     10.0, "mm"),
        param_number("face_dwell", d.face_dwell,
                     "finger slide a landed face stays flat per unit tipping friction (fitted)", 0.0, 50.0, "mm"),
        // The paper's protocol (docs/simulation.md "Protocol")
        param_number("specimen_size_tolerance", d.specimen_size_tolerance,
                     "printing tolerance: a specimen's diameter (cylinder) or edge (prism) is off by uniform +- this, "
                     "once per object and device_seed",
                     0.0, 5.0, "mm"),
        param_bool("specimen_edges", d.specimen_edges,
                   "a prism's edge radii are drawn once per specimen (one printed object); false: afresh per trial"),
        param_number("mount_start_sigma", d.mount_start_sigma,
                     "sigma of a mounting's shift of the start position (the manifest's mount; 0: off, no source)",
                     0.0, 50.0, "mm"),
        param_number("mount_force_log_sigma", d.mount_force_log_sigma,
                     "sigma_ln of a mounting's clamping-load factor (0: off, no source)", 0.0, 2.0, "1"),
        param_number("mount_force_trend", d.mount_force_trend,
                     "relative clamping-load change per 100 rolls of a mounting, e.g. servo warm-up (0: off, no "
                     "source)",
                     -0.9, 0.9, "1"),
        param_number("gain_jitter", d.gain_jitter, "per-device relative gain error of each barometer (uniform +-)",
                     0.0, 0.5, "1"),
        param_number("ambient_offset_range", d.ambient_offset_range,
                     "per-device ambient offset of each barometer (uniform +-), sets quantiser phase", 0.0, 10.0,
                     "kPa"),
        // MPL115A output chain
        param_number("lag_tau", c.lag_tau, "rubber's first-order viscoelastic lag", 0.0, 1.0, "s"),
        param_number("count_kpa", c.count_kpa, "MPL115A output count: (115 - 50) / 1023 kPa per Pcomp count", 0.001, 10.0, "kPa"),
        param_number("kpa_per_unit", c.kpa_per_unit, "pressure per unit of the paper's unitless reading", 0.01,
                     1000.0, "kPa"),
        param_number("noise_kpa", c.noise_kpa, "sigma of the white noise before quantisation", 0.0, 10.0, "kPa"),
        param_number("drift_sigma", c.drift_sigma, "sigma of the per-trial linear drift rate", 0.0, 10.0, "kPa/s"),
        param_number("headroom_kpa", c.headroom_kpa, "saturation pressure above ambient", 0.1, 100.0, "kPa"),
        param_int("baseline_samples", c.baseline_samples,
                  "readings averaged for the no-contact baseline at the start of a recording", 1, 10000),
    };
    const auto hand = etroll::hand_geometry_params();
    const auto at = std::find_if(schema.begin(), schema.end(), [](const ParamSpec& p) { return p.name == "sensor_pitch"; });
    schema.insert(at, hand.begin(), hand.end());
    return schema;
}

SimSettings sim_settings_from(const ParamSet& ps) {
    SimSettings s;
    s.catalogue = ps.get_string("catalogue");
    s.sensing_joint = ps.get_string("sensing_joint");
    s.pushing_joint = ps.get_string("pushing_joint");
    s.palm_joint = ps.get_string("palm_joint");
    SimParameters& p = s.physics;
    p.device_seed = static_cast<std::uint64_t>(ps.get_int("device_seed"));
    p.hand = etroll::hand_geometry_from(ps);
    p.sensor_pitch = ps.get_number("sensor_pitch");
    p.sensor_position_jitter = ps.get_number("sensor_position_jitter");
    p.kernel_fwhm = ps.get_number("kernel_fwhm");
    p.kernel_fwhm_jitter = ps.get_number("kernel_fwhm_jitter");
    p.kernel_tail_at_pitch = ps.get_number("kernel_tail_at_pitch");
    p.kernel_tail_length = ps.get_number("kernel_tail_length");
    p.contact_modulus = ps.get_number("contact_modulus");
    p.foundation_stiffness = ps.get_number("foundation_stiffness");
    p.clamp_line_load = ps.get_number("clamp_line_load");
    p.clamp_reference_current = ps.get_number("clamp_reference_current");
    p.clamp_current_threshold = ps.get_number("clamp_current_threshold");
    p.force_log_sigma = ps.get_number("force_log_sigma");
    p.palm_oscillation = ps.get_number("palm_oscillation");
    p.palm_reference_speed = ps.get_number("palm_reference_speed");
    p.palm_frequency_min = ps.get_number("palm_frequency_min");
    p.palm_frequency_max = ps.get_number("palm_frequency_max");
    p.start_centre = ps.get_number("start_centre");
    p.start_range = ps.get_number("start_range");
    p.start_tilt = ps.get_number("start_tilt");
    p.cylinder_slip_max = ps.get_number("cylinder_slip_max");
    p.polygon_slip = ps.get_number("polygon_slip");
    p.face_dwell = ps.get_number("face_dwell");
    p.specimen_size_tolerance = ps.get_number("specimen_size_tolerance");
    p.specimen_edges = ps.get_bool("specimen_edges");
    p.mount_start_sigma = ps.get_number("mount_start_sigma");
    p.mount_force_log_sigma = ps.get_number("mount_force_log_sigma");
    p.mount_force_trend = ps.get_number("mount_force_trend");
    p.gain_jitter = ps.get_number("gain_jitter");
    p.ambient_offset_range = ps.get_number("ambient_offset_range");
    p.chain.lag_tau = ps.get_number("lag_tau");
    p.chain.count_kpa = ps.get_number("count_kpa");
    p.chain.kpa_per_unit = ps.get_number("kpa_per_unit");
    p.chain.noise_kpa = ps.get_number("noise_kpa");
    p.chain.drift_sigma = ps.get_number("drift_sigma");
    p.chain.headroom_kpa = ps.get_number("headroom_kpa");
    p.chain.baseline_samples = static_cast<int>(ps.get_int("baseline_samples"));
    return s;
}

}  // namespace rollsense::sim
