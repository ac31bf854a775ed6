#include "sim_model.hpp"

#include <algorithm>
#include <cmath>

namespace rollsense::sim {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
}  // namespace

DeviceState make_device(const SimParameters& p) {
    DeviceState d;
    Rng rng(p.device_seed, "device");
    for (int i = 0; i < kChannels; ++i) {
        const auto k = static_cast<std::size_t>(i);
        d.sensor_x[k] = (i - 1) * p.sensor_pitch + rng.uniform(-p.sensor_position_jitter, p.sensor_position_jitter);
        const double fwhm = p.kernel_fwhm * (1.0 + rng.uniform(-p.kernel_fwhm_jitter, p.kernel_fwhm_jitter));
        d.kernel[k] = LayerKernel(fwhm, p.kernel_tail_at_pitch, p.sensor_pitch, p.kernel_tail_length);
        d.gain[k] = 1.0 + rng.uniform(-p.gain_jitter, p.gain_jitter);
        d.ambient_offset[k] = rng.uniform(-p.ambient_offset_range, p.ambient_offset_range);
    }
    return d;
}

namespace {
// The seed of everything that belongs to one specimen (and, with a mount name, to one mounting of it).
std::uint64_t specimen_seed(const SimParameters& p, const std::string& object, const std::string& mount = "") {
    return mix64(p.device_seed) ^ label_hash(mount.empty() ? object : object + "/" + mount);
}
}  // namespace

ObjectSpec make_specimen(const SimParameters& p, const ObjectSpec& nominal) {
    ObjectSpec s = nominal;
    Rng rng(specimen_seed(p, nominal.id), "specimen-size");
    const double deviation = rng.uniform(-p.specimen_size_tolerance, p.specimen_size_tolerance);
    if (s.is_cylinder()) {
        s.diameter += deviation;
    } else {
        s.diameter *= (s.side + deviation) / s.side;  // the circumscribed diameter scales with the edge
        s.side += deviation;
    }
    return s;
}

TrialModel::TrialModel(const SimParameters& params, const DeviceState& device, const ObjectSpec* object,
                       std::uint64_t trial_seed, const MountPosition& mount)
    : p_(params), device_(&device), object_(object), seed_(trial_seed), slip_rng_(trial_seed, "slip") {
    if (object) {
        specimen_ = make_specimen(p_, *object);
        object_ = &*specimen_;
    }
    // Every draw has its own named stream (see rng.hpp).
    Rng placement(trial_seed, "placement");
    draws_.start_centre = placement.uniform(p_.start_centre - 0.5 * p_.start_range,
                                            p_.start_centre + 0.5 * p_.start_range);
    draws_.tilt = placement.normal(0.0, p_.start_tilt * kDeg);
    Rng force(trial_seed, "force");
    draws_.force_factor = std::exp(force.normal(0.0, p_.force_log_sigma));
    draws_.palm_frequency = force.uniform(p_.palm_frequency_min, p_.palm_frequency_max);
    draws_.palm_phase = force.uniform(0.0, 2.0 * kPi);
    Rng slip(trial_seed, "cylinder-slip");
    draws_.cylinder_slip = slip.uniform(0.0, p_.cylinder_slip_max);
    if (object_ && !mount.mount.empty()) {
        // One mounting: where the string holds the specimen, how it is seated,
        // and the slow change over its rolls (all off unless set: no source sizes them).
        Rng m(specimen_seed(p_, object_->id, mount.mount), "mount");
        draws_.start_centre += m.normal(0.0, p_.mount_start_sigma);
        draws_.force_factor *= std::exp(m.normal(0.0, p_.mount_force_log_sigma)) *
                               (1.0 + p_.mount_force_trend * static_cast<double>(mount.index) / 100.0);
    }
    if (object_ && !object_->is_cylinder()) {
        Rng edges = p_.specimen_edges ? Rng(specimen_seed(p_, object_->id), "edges") : Rng(trial_seed, "edges");
        for (int k = 0; k < object_->sides; ++k)
            draws_.edge_radius.push_back(edges.uniform(object_->edge_radius_min, object_->edge_radius_max));
    }
}

void TrialModel::start(double time, double theta) {
    // Each recording restarts the output chain (its baseline is taken at the
    // recording's start); the first of a trial draws the named noise streams,
    // later ones their own, so that a back pass is not a copy of the forward one.
    const std::string pass = recordings_ == 0 ? "" : "-rec" + std::to_string(recordings_ + 1);
    for (int i = 0; i < kChannels; ++i) {
        const auto k = static_cast<std::size_t>(i);
        channels_[k] = OutputChannel(p_.chain, device_->gain[k], device_->ambient_offset[k]);
        channels_[k].begin_trial(Rng(seed_, (i == 0 ? "noise-ch1" : i == 1 ? "noise-ch2" : "noise-ch3") + pass), time);
    }
    last_theta_ = theta;
    last_time_ = time;
    start_time_ = time;
    speed_ = 0.0;
    started_ = true;
    // The object is placed once per trial, at its first recording. A later
    // recording (a back pass) finds it where the fingers have rolled it: it
    // follows the finger angle from there, so rolling back crosses the
    // barometers again instead of starting from a fresh placement.
    if (recordings_++ > 0) return;
    cylinder_.reset();
    polygon_.reset();
    slip_rng_ = Rng(seed_, "slip");
    if (object_ && object_->is_cylinder()) {
        cylinder_.emplace(p_.hand, object_->diameter, draws_.start_centre, theta, draws_.cylinder_slip);
    } else if (object_) {
        PolygonShape shape{object_->sides, object_->side, draws_.edge_radius};
        polygon_.emplace(p_.hand, shape, draws_.start_centre,
                         PolygonTumbler::flat_orientation(object_->sides) + draws_.tilt, theta);
    }
    line_load_prev_ = 0.0;
}

void TrialModel::compute_stress(double time, double theta, double clamp_current) {
    stress_.fill(0.0);
    line_load_ = 0.0;
    // Finger speed from the angles the actuator reported (not from a schedule).
    const double dt = time - last_time_;
    if (dt > 0.0) {
        const double raw = (theta - last_theta_) / dt;
        speed_ = speed_ == 0.0 ? raw : 0.5 * (speed_ + raw);
    }
    last_theta_ = theta;
    last_time_ = time;

    // Kinematics follow the fingers whether or not the object is pressed.
    double lever = p_.hand.array_distance;
    if (cylinder_) {
        contact_ = cylinder_->contact(theta);
        lever = cylinder_->lever_arm(theta);
    } else if (polygon_) {
        // A landing face's dwell scales with the tangential force it must build,
        // i.e. with the clamping load (the previous sample's; it varies slowly).
        const double load_ratio = (line_load_prev_ > 0.0 ? line_load_prev_ : p_.clamp_line_load * draws_.force_factor) /
                                  p_.clamp_line_load;
        polygon_->set_dwell(p_.face_dwell * load_ratio, p_.polygon_slip, &slip_rng_);
        polygon_->advance(theta);
    }
    if (!object_ || std::abs(clamp_current) < p_.clamp_current_threshold) return;

    // Clamping load: constant torque over the pushing finger's lever arm, the
    // trial's force draw, and the palm controller's oscillation at low speed.
    double load = p_.clamp_line_load * draws_.force_factor;
    if (p_.clamp_reference_current > 0.0) load *= std::abs(clamp_current) / p_.clamp_reference_current;
    const double omega = std::abs(speed_) / kDeg;  // deg/s
    double modulation = 0.0;
    if (omega > 0.2 * p_.palm_reference_speed)
        modulation = p_.palm_oscillation * std::min(2.0, p_.palm_reference_speed / omega);
    load *= 1.0 + modulation * std::sin(2.0 * kPi * draws_.palm_frequency * (time - start_time_) + draws_.palm_phase);

    if (cylinder_) {
        load *= p_.hand.array_distance / std::max(lever, 10.0);
        line_load_ = load;
        const double b = hertz_half_width(load, 0.5 * object_->diameter, p_.contact_modulus);
        const double spread_var = 0.25 * b * b;
        for (std::size_t i = 0; i < kChannels; ++i)
            stress_[i] = 1000.0 * load * device_->kernel[i].spread(device_->sensor_x[i] - contact_, spread_var);
        return;
    }
    PolygonContact c = polygon_->contact();
    load *= p_.hand.array_distance / std::max(c.lever_arm, 10.0);
    line_load_ = load;
    line_load_prev_ = load;
    contact_ = c.contact;
    const PivotLoad pl = winkler_pivot_load(
        PivotProfile{c.contact, c.slope_rear, c.slope_front, c.extent_rear, c.extent_front}, load,
        p_.foundation_stiffness);
    // Rear and front faces meet at the pivot: one continuous piecewise-linear load.
    const PressureSegment& rear = pl.segments[0];
    const PressureSegment& front = pl.segments[1];
    for (std::size_t i = 0; i < kChannels; ++i)
        stress_[i] = 1000.0 * device_->kernel[i].two_segments(device_->sensor_x[i], rear.u0, rear.u1, front.u1, rear.p0,
                                                              rear.p1, front.p1);
}

std::array<double, kChannels> TrialModel::sample(double time, double theta, double clamp_current) {
    if (!started_) start(time, theta);
    compute_stress(time, theta, clamp_current);
    std::array<double, kChannels> out{};
    for (std::size_t i = 0; i < kChannels; ++i) out[i] = channels_[i].sample(time, stress_[i]);
    return out;
}

}  // namespace rollsense::sim
