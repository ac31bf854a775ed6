#include "replay_sensor.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include "rollsense/csv.hpp"
#include "rollsense/log.hpp"

namespace rollsense::plugins::replay {

namespace fs = std::filesystem;

namespace {
constexpr const char* kDefaultCheckJoint = "sensing_finger";
}  // namespace

ParamSchema replay_schema() {
    return {
        param_string("dataset", std::nullopt,
                     "folder of the dataset to replay (what `rollsense run --out DIR` wrote, or a hand-made one; "
                     "docs/dataset-format.md)"),
        param_string("select", std::string("match"),
                     "which recorded trial a script's trial plays: 'match' (same id, else same object/speed/"
                     "repetition) or 'order' (the next one in manifest order)",
                     {"match", "order"}),
        param_string("past_end", std::string("invalid"),
                     "a read after the recording's end: 'invalid' (NaN, frame invalid with the reason) or 'hold' "
                     "(the last recorded sample)",
                     {"invalid", "hold"}),
        param_string("check_joint", std::string(kDefaultCheckJoint),
                     "joint whose live angle is compared with the recorded one ('' = no check)"),
        param_number("angle_tolerance", 2.0, "largest difference between live and recorded angle before a warning",
                     0.0, {}, "deg"),
        param_string("on_mismatch", std::string("warn"),
                     "when the roll differs from the recording's: 'warn' (once per trial, summary at the end) or "
                     "'invalid' (also mark those frames invalid)",
                     {"warn", "invalid"}),
    };
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void fill_invalid(Frame& out, std::string reason) {
    for (auto& v : out.values) v = kNaN;
    out.valid = false;
    out.reason = std::move(reason);
}

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", v);
    return buf;
}

// A select argument as text: Lua hands numbers over as integers or doubles.
Result<std::string> arg_text(const std::string& key, const ParamValue& v) {
    if (auto s = std::get_if<std::string>(&v)) return *s;
    if (auto i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
    if (auto d = std::get_if<double>(&v)) return csv::format_number(*d);
    return Error{ErrorCode::invalid_argument, "select: '" + key + "' must be a string or a number, not " +
                                                  format_param_value(v)};
}

Result<std::int64_t> arg_integer(const std::string& key, const ParamValue& v) {
    if (auto i = std::get_if<std::int64_t>(&v)) return *i;
    if (auto d = std::get_if<double>(&v); d && std::floor(*d) == *d && std::isfinite(*d))
        return static_cast<std::int64_t>(*d);
    if (auto s = std::get_if<std::string>(&v)) {
        auto n = csv::parse_number(*s, "select: '" + key + "'");
        if (n && std::floor(*n) == *n) return static_cast<std::int64_t>(*n);
    }
    return Error{ErrorCode::invalid_argument, "select: '" + key + "' must be a whole number, not " +
                                                  format_param_value(v)};
}

}  // namespace

std::string ReplaySensor::source() const { return instance_.empty() ? "replay" : instance_; }

std::string ReplaySensor::dataset_name() const { return dataset_ ? dataset_->dir().string() : dataset_param_; }

std::string ReplaySensor::setting(const std::string& param) const {
    return "--set devices." + (instance_.empty() ? std::string("tactile") : instance_) + ".params." + param;
}

// ---------------------------------------------------------------- lifecycle --

Status ReplaySensor::on_configure(const ParamSet& p, const PluginContext& context) {
    instance_ = context.instance;
    dataset_param_ = p.get_string("dataset");
    select_ = p.get_string("select") == "order" ? Select::order : Select::match;
    past_end_ = p.get_string("past_end") == "hold" ? PastEnd::hold : PastEnd::invalid;
    on_mismatch_ = p.get_string("on_mismatch") == "invalid" ? OnMismatch::invalid : OnMismatch::warn;
    check_joint_ = p.get_string("check_joint");
    angle_tolerance_ = p.get_number("angle_tolerance");
    if (dataset_param_.empty())
        return {ErrorCode::invalid_argument,
                "parameter 'dataset' is empty: pass the folder to replay, e.g. --set dataset=runs/2024-05-01"};

    fs::path dir = dataset_param_;
    auto opened = DatasetReader::open(dir);
    if (!opened) {
        std::string hint;
        std::error_code ec;
        if (dir.is_relative()) hint = " (relative to the working directory " + fs::current_path(ec).string() + ")";
        return {opened.error().code, "cannot replay dataset '" + dataset_param_ + "'" + hint + ": " +
                                         opened.error().message};
    }
    dataset_ = std::move(*opened);
    const auto& info = dataset_->info();
    if (dataset_->trials().empty())
        return {ErrorCode::parse_error, (dir / "manifest.csv").string() + ": lists no trials; nothing to replay"};
    if (info.channels.empty())
        return {ErrorCode::parse_error, dataset_name() +
                                            ": no sensor channel columns (hand-made trial files name them ch1, "
                                            "ch2, ...; docs/dataset-format.md)"};
    channels_.clear();
    for (std::size_t c = 0; c < info.channels.size(); ++c) {
        const std::string& name = info.channels[c];
        if (name.empty() || name.find_first_of(", \"\n\r") != std::string::npos)
            return {ErrorCode::parse_error, dataset_name() + ": channel column '" + name +
                                                "' cannot be recorded again (no spaces, commas or quotes in "
                                                "column names)"};
        // The recorded unit when the dataset states it; a hand-made dataset's
        // columns are the paper's unitless reading (docs/dataset-format.md).
        const std::string unit = c < info.channel_units.size() ? info.channel_units[c] : "1";
        channels_.push_back({name, unit, "column '" + name + "' replayed from " + dataset_name()});
    }
    if (auto st = find_check_column(dir); !st) return st;
    reset_trial_state();
    log_info(source(), "replaying " + std::to_string(dataset_->trials().size()) + " trials of " + dataset_name() +
                           " (" + std::to_string(channels_.size()) + " channels, recorded with seed " +
                           std::to_string(info.seed) + ")");
    return {};
}

void ReplaySensor::reset_trial_state() {
    pinned_.reset();
    current_.reset();
    next_in_order_ = 0;
    seed_warned_ = false;
    joint_missing_warned_ = false;
    seed_mismatches_ = 0;
    trials_played_ = 0;
}

Status ReplaySensor::on_cleanup() {
    reset_trial_state();
    dataset_.reset();
    channels_.clear();
    return {};
}

Status ReplaySensor::on_recover() { return on_cleanup(); }

Status ReplaySensor::find_check_column(const fs::path& dir) {
    check_column_.reset();
    if (check_joint_.empty()) return {};
    const auto& joints = dataset_->info().joints;
    for (std::size_t j = 0; j < joints.size(); ++j)
        if (joints[j] == check_joint_) check_column_ = j;
    if (check_column_) return {};
    // Only the default may find no column, on a dataset with nothing to check
    // (hand-made, or no joint recorded): a joint named on purpose (a typo), or a
    // recording whose hand names its finger otherwise, would turn the check off unseen.
    if (check_joint_ == kDefaultCheckJoint && (joints.empty() || !fs::exists(dir / "dataset-info.csv"))) {
        log_info(source(), dataset_name() + " recorded no '" + check_joint_ +
                               "' column: the script's roll is not checked against the recording");
        return {};
    }
    std::string recorded;
    for (const auto& j : joints) recorded += (recorded.empty() ? "" : ", ") + j;
    return {ErrorCode::invalid_argument,
            "parameter 'check_joint' = '" + check_joint_ + "': " + dataset_name() + " recorded no such joint column (" +
                (joints.empty() ? std::string("it recorded none") : "its joint columns: " + recorded) +
                "); name one with " + setting("check_joint") + "=JOINT, or " + setting("check_joint") +
                "='' to replay without checking the roll"};
}

// ------------------------------------------------------------------- trials --

Result<std::size_t> ReplaySensor::choose(const TrialInfo& trial) {
    const auto& trials = dataset_->trials();
    if (pinned_) {
        auto query = *pinned_;
        pinned_.reset();
        return find_trial(trials, query, dataset_name());
    }
    if (select_ == Select::order) {
        if (next_in_order_ >= trials.size())
            return Error{ErrorCode::not_found, "all " + std::to_string(trials.size()) + " trials of dataset " +
                                                   dataset_name() + " have been played (select = 'order'); the "
                                                   "script began trial '" + trial.id + "' after them"};
        return next_in_order_;
    }
    auto found = match_script_trial(trials, trial, dataset_name());
    if (!found)
        return Error{found.error().code,
                     found.error().message +
                         ". Replay with the settings it was recorded with (its run-info.csv has the command line), "
                         "or play the recorded trials in order with " + setting("select") + "=order"};
    return found;
}

Status ReplaySensor::begin_trial(const TrialInfo& trial) {
    if (!dataset_) return {ErrorCode::state_error, "begin_trial before configure: no dataset is open"};
    current_.reset();  // the previous trial's samples go, whatever happens next
    auto index = choose(trial);
    if (!index) return index.status();
    next_in_order_ = *index + 1;
    const TrialRecord& record = dataset_->trials()[*index];
    auto data = dataset_->load(record);
    if (!data) return {data.error().code, "trial '" + record.info.id + "': " + data.error().message};
    if (data->samples() == 0)
        return {ErrorCode::parse_error, (dataset_->dir() / record.file).string() +
                                            ": no samples (a trial file needs at least one row after the header)"};

    if (record.info.id == trial.id && record.info.seed != 0 && trial.seed != 0 && record.info.seed != trial.seed) {
        ++seed_mismatches_;
        if (!seed_warned_) {
            seed_warned_ = true;
            log_warning(source(), "trial '" + trial.id + "' was recorded in a run with another --seed (the dataset's "
                                  "run seed is " + std::to_string(dataset_->info().seed) +
                                  "): the procedure's jittered recording margins differ, so the roll will not line "
                                  "up with the recording and sample counts will differ; rerun with --seed " +
                                  std::to_string(dataset_->info().seed) + " to reproduce it");
        }
    }
    if (!trial.object.empty() && record.info.object != trial.object)
        log_warning(source(), "the script's trial '" + trial.id + "' is object " + trial.object +
                                  ", the recording played ('" + record.info.id + "') is object " +
                                  record.info.object);

    Current c;
    c.index = *index;
    c.playback = Playback(data->time, 1.0 / dataset_->info().sample_rate_hz);
    c.data = std::move(*data);
    current_ = std::move(c);
    log_debug(source(), "trial '" + trial.id + "' plays '" + record.info.id + "' (" + record.file + ", " +
                            std::to_string(current_->data.samples()) + " samples)");
    return {};
}

Status ReplaySensor::start_recording(const SampleInput& input) {
    if (!current_)
        return {ErrorCode::state_error, "recording started without a trial: the script must call rs.trial{...} "
                                        "first, so the replay knows which recording to play"};
    current_->playback.start(input.time);
    current_->recording = true;
    current_->mismatches = 0;
    current_->max_angle_error = 0.0;
    return {};
}

void ReplaySensor::check_roll(const SampleInput& input, std::size_t index, Frame& out) {
    if (check_joint_.empty() || !check_column_) return;
    const JointState* joint = input.joint(check_joint_);
    if (!joint) {
        if (!joint_missing_warned_) {
            joint_missing_warned_ = true;
            log_warning(source(), "no joint '" + check_joint_ +
                                      "' in this profile: the roll is not checked against the recording (set "
                                      "check_joint to the joint that rolls, or '' to silence this)");
        }
        return;
    }
    const double recorded = current_->data.joints[*check_column_][index];
    if (!std::isfinite(recorded)) return;
    const double error = std::fabs(joint->position - recorded);
    current_->max_angle_error = std::max(current_->max_angle_error, error);
    if (error <= angle_tolerance_) return;
    const std::string what = check_joint_ + " at " + fmt(joint->position) + ", the recording had " + fmt(recorded) +
                             " (tolerance " + fmt(angle_tolerance_) + ")";
    if (current_->mismatches++ == 0)
        log_warning(source(), "trial '" + dataset_->trials()[current_->index].info.id + "', " +
                                  fmt(input.time - current_->playback.start_time()) +
                                  " s into the recording: the script's roll does not match the recording's: " +
                                  what);
    if (on_mismatch_ == OnMismatch::invalid && out.valid) {
        out.valid = false;
        out.reason = "roll does not match the recording: " + what;
    }
}

Status ReplaySensor::read(const SampleInput& input, Frame& out) {
    if (!current_ || !current_->recording)
        return {ErrorCode::state_error, "read outside a recording (start_recording was not called)"};
    const auto& record = dataset_->trials()[current_->index];
    const auto& data = current_->data;
    auto pos = current_->playback.locate(input.time);
    if (pos.before_start) {
        fill_invalid(out, "t=" + fmt(input.time) + " s is before the recording started");
        return {};
    }
    bool held = false;
    if (pos.past_end) {
        if (past_end_ == PastEnd::invalid) {
            fill_invalid(out, "past the end of the recording of trial '" + record.info.id + "' (" +
                                  std::to_string(data.samples()) + " samples, " +
                                  fmt(current_->playback.duration()) +
                                  " s): the script records longer than the recording did");
            return {};
        }
        pos.index = data.samples() - 1;
        held = true;
    }
    const std::size_t i = pos.index;
    for (std::size_t c = 0; c < out.values.size() && c < data.channels.size(); ++c) out.values[c] = data.channels[c][i];
    if (!data.valid[i]) {
        out.valid = false;
        out.reason = "sample " + std::to_string(i + 1) + " of " + record.file + " was recorded as invalid";
    } else {
        for (std::size_t c = 0; c < out.values.size(); ++c)
            if (!std::isfinite(out.values[c])) {
                out.valid = false;
                out.reason = "sample " + std::to_string(i + 1) + " of " + record.file + " holds " +
                             csv::format_number(out.values[c]) + " in column '" + channels_[c].name + "'";
                break;
            }
    }
    if (!held) check_roll(input, i, out);
    return {};
}

Status ReplaySensor::stop_recording() {
    if (!current_ || !current_->recording) return {};
    current_->recording = false;
    const auto& pb = current_->playback;
    const std::string id = dataset_->trials()[current_->index].info.id;
    const std::size_t n = pb.samples();
    if (pb.past_end() > 0)
        log_warning(source(), "trial '" + id + "': " + std::to_string(pb.past_end()) +
                                  " reads came after the recording's end (" + std::to_string(n) + " samples); " +
                                  (past_end_ == PastEnd::invalid ? "they are invalid frames"
                                                                 : "they hold the last recorded sample"));
    else if (pb.last_index() == n || pb.last_index() + 1 < n)
        log_warning(source(), "trial '" + id + "': recording stopped after " +
                                  std::to_string(pb.last_index() == n ? 0 : pb.last_index() + 1) + " of " +
                                  std::to_string(n) + " recorded samples; the rest was not replayed");
    if (pb.repeated() > 0 || pb.skipped() > 0)
        log_info(source(), "trial '" + id + "': the recording's rate differs from the sampling rate: " +
                               std::to_string(pb.repeated()) + " samples served again, " +
                               std::to_string(pb.skipped()) + " skipped");
    if (current_->mismatches > 0)
        log_warning(source(), "trial '" + id + "': the " + check_joint_ + " differed from the recording at " +
                                  std::to_string(current_->mismatches) + " samples (up to " +
                                  fmt(current_->max_angle_error) + ")");
    return {};
}

Status ReplaySensor::end_trial() {
    if (current_) {
        (void)stop_recording();
        ++trials_played_;
    }
    current_.reset();  // streaming: one trial in memory at a time
    return {};
}

// --------------------------------------------------------------- operations --

ValueMap ReplaySensor::describe(std::size_t index) const {
    const auto& r = dataset_->trials()[index];
    return {{"id", r.info.id},
            {"object", r.info.object},
            {"speed", r.info.speed},
            {"repetition", static_cast<std::int64_t>(r.info.repetition)},
            {"samples", static_cast<std::int64_t>(r.samples)},
            {"index", static_cast<std::int64_t>(index + 1)},
            {"file", r.file}};
}

Result<ValueMap> ReplaySensor::select(const ValueMap& args) {
    TrialQuery q;
    for (const auto& [key, value] : args) {
        if (key == "id" || key == "object" || key == "speed") {
            auto text = arg_text(key, value);
            if (!text) return text.error();
            (key == "id" ? q.id : key == "object" ? q.object : q.speed) = *text;
        } else if (key == "repetition" || key == "index") {
            auto n = arg_integer(key, value);
            if (!n) return n.error();
            if (key == "repetition") {
                q.repetition = static_cast<int>(*n);
            } else {
                if (*n < 1) return Error{ErrorCode::invalid_argument, "select: index counts from 1"};
                q.index = static_cast<std::size_t>(*n - 1);
            }
        } else {
            return Error{ErrorCode::invalid_argument,
                         "select: unknown argument '" + key + "' (known: id, object, speed, repetition, index)"};
        }
    }
    if (q.empty()) q.index = next_in_order_;  // no argument: the next one in manifest order
    auto found = find_trial(dataset_->trials(), q, dataset_name());
    if (!found) return found.error();
    pinned_ = TrialQuery{};
    pinned_->index = *found;
    return describe(*found);
}

ValueMap ReplaySensor::status_map() const {
    ValueMap m{{"dataset", dataset_name()},
               {"trials", static_cast<std::int64_t>(dataset_ ? dataset_->trials().size() : 0)},
               {"trials_played", static_cast<std::int64_t>(trials_played_)},
               {"seed_mismatches", static_cast<std::int64_t>(seed_mismatches_)}};
    if (current_) {
        const auto& pb = current_->playback;
        m["trial"] = dataset_->trials()[current_->index].info.id;
        m["recorded_samples"] = static_cast<std::int64_t>(pb.samples());
        m["reads"] = static_cast<std::int64_t>(pb.reads());
        m["served"] = static_cast<std::int64_t>(pb.distinct_served());
        m["repeated"] = static_cast<std::int64_t>(pb.repeated());
        m["skipped"] = static_cast<std::int64_t>(pb.skipped());
        m["past_end"] = static_cast<std::int64_t>(pb.past_end());
        m["roll_mismatches"] = static_cast<std::int64_t>(current_->mismatches);
        m["max_angle_error"] = current_->max_angle_error;
    }
    return m;
}

Result<ValueMap> ReplaySensor::invoke(const std::string& verb, const ValueMap& args) {
    if (!dataset_) return Error{ErrorCode::state_error, "'" + verb + "': no dataset is open (configure first)"};
    if (verb == "select") return select(args);
    if (verb == "status") return status_map();
    if (verb == "trials") {
        std::vector<std::string> ids, objects, speeds;
        std::vector<std::int64_t> reps, samples;
        for (const auto& r : dataset_->trials()) {
            ids.push_back(r.info.id);
            objects.push_back(r.info.object);
            speeds.push_back(r.info.speed);
            reps.push_back(r.info.repetition);
            samples.push_back(static_cast<std::int64_t>(r.samples));
        }
        return ValueMap{{"count", static_cast<std::int64_t>(ids.size())},
                        {"ids", ids},
                        {"objects", objects},
                        {"speeds", speeds},
                        {"repetitions", reps},
                        {"samples", samples},
                        {"dataset", dataset_name()},
                        {"seed", static_cast<std::int64_t>(dataset_->info().seed)},
                        {"sample_rate_hz", dataset_->info().sample_rate_hz}};
    }
    return Error{ErrorCode::unsupported,
                 "no operation '" + verb + "' (the replay sensor has: select, trials, status)"};
}

}  // namespace rollsense::plugins::replay
