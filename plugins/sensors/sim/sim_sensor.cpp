#include "sim_sensor.hpp"

#include <cmath>

#include "rollsense/log.hpp"

namespace rollsense::sim {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::string joint_list(const SampleInput& input) {
    std::string out;
    if (input.joint_names)
        for (const auto& n : *input.joint_names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? "none" : out;
}

// The trial's place in the protocol, from the manifest's extra keys `mount`
// and `index_in_mount` (etroll.run_trial writes them); none: no mount effects.
Result<MountPosition> mount_position(const TrialInfo& trial) {
    MountPosition m;
    if (auto it = trial.extra.find("mount"); it != trial.extra.end()) m.mount = it->second;
    if (auto it = trial.extra.find("index_in_mount"); it != trial.extra.end()) {
        const std::string& text = it->second;
        std::size_t used = 0;
        try {
            m.index = std::stol(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != text.size() || m.index < 0)
            return Error{ErrorCode::invalid_argument, "sim: trial '" + trial.id + "': index_in_mount '" + text +
                                                          "' is not an integer >= 0 (rolls before this one in its "
                                                          "mounting; etroll.run_trial's index_in_mount)"};
    }
    return m;
}
}  // namespace

Status SimSensor::on_configure(const ParamSet& params, const PluginContext& context) {
    settings_ = sim_settings_from(params);
    context_ = context;
    if (settings_.physics.palm_frequency_max < settings_.physics.palm_frequency_min)
        return Status{ErrorCode::invalid_argument, "sim: palm_frequency_max (" +
                                                       std::to_string(settings_.physics.palm_frequency_max) +
                                                       " Hz) is below palm_frequency_min; swap them"};
    std::filesystem::path file = settings_.catalogue;
    if (file.is_relative()) file = context.share_dir / file;
    auto loaded = ObjectCatalogue::load(file);
    if (!loaded)
        return Status{loaded.error()}.with_context("sim sensor '" + context.instance +
                                                   "', 'catalogue' parameter");
    catalogue_ = std::move(loaded.value());
    device_ = make_device(settings_.physics);
    object_ = nullptr;
    trial_ = std::make_unique<TrialModel>(settings_.physics, device_, nullptr, 0);
    return {};
}

Status SimSensor::on_cleanup() {
    trial_.reset();
    object_ = nullptr;
    catalogue_.reset();
    return {};
}

Status SimSensor::on_recover() { return on_cleanup(); }

std::vector<ChannelInfo> SimSensor::channels() const {
    return {{"ch1", "1", "simulated barometer 1 (first crossed), baseline-subtracted, unitless"},
            {"ch2", "1", "simulated barometer 2 (middle), baseline-subtracted, unitless"},
            {"ch3", "1", "simulated barometer 3 (last crossed), baseline-subtracted, unitless"}};
}

Status SimSensor::begin_trial(const TrialInfo& trial) {
    if (!catalogue_) return Status{ErrorCode::state_error, "sim: begin_trial before on_configure"};
    trial_info_ = trial;
    object_ = nullptr;
    if (!trial.object.empty()) {
        object_ = catalogue_->find(trial.object);
        if (!object_)
            return Status{ErrorCode::not_found, "sim: object '" + trial.object + "' of trial '" + trial.id +
                                                    "' is not in the catalogue " + catalogue_->path().string() +
                                                    " (known: " + catalogue_->ids() +
                                                    "); add a row there or fix the script's object id"};
        // The reader checks every row; checked again here because a NaN or
        // huge length would make the tumbling model index out of bounds or
        // step for minutes, whoever filled the catalogue.
        if (auto problem = object_problem(*object_))
            return Status{ErrorCode::invalid_argument, "sim: object '" + object_->id + "' of catalogue " +
                                                           catalogue_->path().string() + ", column '" +
                                                           problem->column + "': " + problem->message};
    }
    auto mount = mount_position(trial);
    if (!mount) return Status{mount.error()};
    trial_ = std::make_unique<TrialModel>(settings_.physics, device_, object_, trial.seed, *mount);
    warned_no_pushing_joint_ = false;
    return {};
}

Result<double> SimSensor::finger_angle(const SampleInput& input) const {
    const JointState* j = input.joint(settings_.sensing_joint);
    if (!j)
        return Error{ErrorCode::not_found, "sim: the sample carries no joint '" + settings_.sensing_joint +
                                               "' (joints: " + joint_list(input) +
                                               "); set the sim sensor's 'sensing_joint' parameter to the joint "
                                               "that turns the sensing finger"};
    return j->position * kDeg;
}

double SimSensor::clamp_current(const SampleInput& input) {
    const JointState* j = input.joint(settings_.pushing_joint);
    if (!j) {
        if (object_ && !warned_no_pushing_joint_) {
            log_warning("sim", "no joint '" + settings_.pushing_joint + "' in the sample (joints: " +
                                   joint_list(input) + "): the object counts as not clamped; set 'pushing_joint'");
            warned_no_pushing_joint_ = true;
        }
        return 0.0;
    }
    return j->current;
}

Status SimSensor::start_recording(const SampleInput& input) {
    if (!trial_) return Status{ErrorCode::state_error, "sim: start_recording before on_configure"};
    double theta = 0.0;
    if (object_) {
        auto angle = finger_angle(input);
        if (!angle) return Status{angle.error()};
        theta = angle.value();
    } else if (auto angle = finger_angle(input)) {
        theta = angle.value();
    }
    trial_->start(input.time, theta);
    return {};
}

Status SimSensor::read(const SampleInput& input, Frame& out) {
    if (!trial_) return Status{ErrorCode::state_error, "sim: read before on_configure"};
    double theta = 0.0;
    if (auto angle = finger_angle(input)) {
        theta = angle.value();
    } else if (object_) {
        return Status{angle.error()};
    }
    if (const JointState* palm = input.joint(settings_.palm_joint)) {
        last_palm_width_ = palm->position;
        have_palm_width_ = true;
    }
    const auto values = trial_->sample(input.time, theta, clamp_current(input));
    out.time = input.time;
    out.values.assign(values.begin(), values.end());
    out.valid = true;
    out.reason.clear();
    return {};
}

Status SimSensor::stop_recording() { return {}; }

Status SimSensor::end_trial() {
    object_ = nullptr;
    trial_ = std::make_unique<TrialModel>(settings_.physics, device_, nullptr, 0);
    return {};
}

// Operations for scripts and diagnostics:
//   "objects"  → ids (string list) of the catalogue
//   "state"    → the present contact position (mm), clamping load (N/mm),
//                palm width the model needs vs the one the actuator reports
Result<ValueMap> SimSensor::invoke(const std::string& verb, const ValueMap& args) {
    (void)args;
    if (verb == "objects") {
        if (!catalogue_) return Error{ErrorCode::state_error, "sim: not configured"};
        std::vector<std::string> ids;
        for (const auto& o : catalogue_->objects()) ids.push_back(o.id);
        return ValueMap{{"ids", ids}, {"catalogue", catalogue_->path().string()}};
    }
    if (verb == "state") {
        if (!trial_) return Error{ErrorCode::state_error, "sim: not configured"};
        ValueMap m{{"object", object_ ? object_->id : std::string()},
                   {"contact_mm", trial_->contact_position()},
                   {"line_load_n_per_mm", trial_->line_load()}};
        if (const PolygonTumbler* t = trial_->tumbler()) {
            const PolygonContact c = t->contact();
            m["landings"] = static_cast<std::int64_t>(t->landings());
            m["model_palm_width_mm"] = settings_.physics.hand.palm_width(c.gap, t->theta());
            m["dwelling"] = c.dwelling;
        }
        if (have_palm_width_) m["reported_palm_width_mm"] = last_palm_width_;
        return m;
    }
    return Error{ErrorCode::unsupported, "sim: no operation '" + verb + "' (known: objects, state)"};
}

}  // namespace rollsense::sim
