#include "runtime/session/recorder.hpp"

#include <cmath>
#include <utility>

#include "rollsense/log.hpp"
#include "rollsense/random.hpp"
#include "rollsense/trial_id.hpp"
#include "runtime/robot/robot.hpp"
#include "runtime/time/clock.hpp"

namespace rollsense::runtime {

Recorder::Recorder(Robot& robot, const Clock& clock, double sample_rate_hz, std::uint64_t run_seed)
    : robot_(robot), clock_(clock), sample_period_(1.0 / sample_rate_hz), run_seed_(run_seed), run_rng_(run_seed) {}

Recorder::~Recorder() = default;

std::uint64_t Recorder::trial_seed(std::uint64_t run_seed, const std::string& trial_id) {
    // FNV-1a of the id, with the offset basis this project has always used (1469598103934665603, not FNV's
    // 14695981039346656037): every recorded dataset's trial seeds depend on it, so it stays.
    std::uint64_t h = 1469598103934665603ULL;
    for (unsigned char c : trial_id) h = (h ^ c) * 1099511628211ULL;
    return random::splitmix64(run_seed ^ h);
}

Status Recorder::open_dataset(const std::filesystem::path& dir, const DatasetInfo& info, bool resume,
                              std::size_t commit_every) {
    auto w = DatasetWriter::open(dir, info, resume ? DatasetOpenMode::resume : DatasetOpenMode::create);
    if (!w) return w.status();
    dataset_ = std::move(*w);
    dataset_->set_commit_every(commit_every);
    dataset_->set_on_durable(on_durable_);
    return {};
}

Status Recorder::begin_trial(TrialInfo info) {
    if (recording_) return {ErrorCode::state_error, "a trial cannot begin while recording (call rs.record_stop() first)"};
    // The id names the trial's file: checked here so rs.trial fails at once,
    // not a batch of trials later when the file cannot be created.
    if (auto s = check_trial_info(info); !s.ok()) return s;
    warn_unsaved("by the next rs.trial");
    info.seed = trial_seed(run_seed_, info.id);
    trial_ = std::move(info);
    trial_rng_.seed(trial_.seed);
    data_ = TrialData{};
    auto s = robot_.begin_trial(trial_);
    trial_open_ = s.ok();  // one the devices refused is not open (review: it was recorded and saved all the same)
    return s;
}

Status Recorder::can_start() const {
    if (!trial_open_) return {ErrorCode::state_error, "recording needs a trial: call rs.trial{object=..., ...} first"};
    if (recording_) return {ErrorCode::state_error, "already recording"};
    return {};
}

Status Recorder::start(double now) {
    if (auto s = can_start(); !s.ok()) return s;
    if (auto s = robot_.start_recording(now); !s.ok()) return s;
    data_ = TrialData{};
    data_.channels.resize(robot_.channel_columns().size());
    data_.joints.resize(robot_.recorded_joints().size());
    recording_ = unsaved_ = true;
    sample_epoch_ = now;
    sample_m_ = 0;
    next_sample_ = now;
    return {};
}

Status Recorder::stop() {
    if (!recording_) return {ErrorCode::state_error, "not recording"};
    recording_ = false;
    return robot_.stop_recording();
}

Status Recorder::sample_tick(double now) {
    const std::size_t bytes = data_.samples() * (8 * (1 + data_.channels.size() + data_.joints.size()) + 1);
    if (auto s = bytes <= max_recording_bytes ? robot_.sample(now, data_) : Status{ErrorCode::limit_violation,
            "trial '" + trial_.id + "': its recording reached the memory cap (--memory-limit-mb) after " +
                std::to_string(data_.samples()) + " samples: stop it with rs.record_stop(), or raise the cap"}; !s.ok()) {
        recording_ = false;  // review: a forgotten record_stop() grew the recording by 45 MB a second
        return s;
    }
    // Time since the recording started, from the sample index: identical for
    // identical trials wherever they fall in a run.
    data_.time.back() = std::round(static_cast<double>(sample_m_) * sample_period_ * 1e6) / 1e6;
    ++sample_m_;
    next_sample_ = sample_epoch_ + clock_.quantize(static_cast<double>(sample_m_) * sample_period_);
    if (on_sample) on_sample();
    return {};
}

// Review (Lua scripts): a trial left unsaved for the next rs.trial or for the script's end was dropped without a word.
void Recorder::warn_unsaved(const char* when) {
    if (std::exchange(unsaved_, false) && trial_open_)
        log_warning("kernel", "trial '" + trial_.id + "': its " + std::to_string(data_.samples()) + " samples were not "
                    "saved, discarded " + when + " (rs.save_trial() keeps a trial, rs.end_trial() drops it quietly)");
}

void Recorder::abort_recording() {
    if (!recording_) return;
    recording_ = false;
    if (auto s = robot_.stop_recording(); !s.ok()) log_error("kernel", "stopping the recording: " + s.message());
}

Status Recorder::save_trial() {
    if (!dataset_) return {ErrorCode::state_error, "no dataset is open: run with --out DIR to save trials"};
    if (recording_) return {ErrorCode::state_error, "stop recording before saving the trial"};
    if (data_.samples() == 0)  // review: with no trial begun, this said "trial '' recorded no samples"
        return {ErrorCode::state_error, trial_open_ ? "trial '" + trial_.id + "' recorded no samples: record it first"
                                                    : "no trial to save: rs.trial{...} first"};
    if (plan_)
        if (auto s = plan_->check_save(trial_.id); !s.ok()) return s;
    TrialRecord rec;
    rec.info = trial_;
    auto s = dataset_->add_trial(rec, data_);
    if (s.ok()) ++trials_accepted_;
    unsaved_ = unsaved_ && !s.ok();
    return s;
}

Status Recorder::end_trial() {
    if (recording_)
        if (auto s = stop(); !s.ok()) log_error("kernel", "ending the trial: " + s.message());  // nobody else sees it
    trial_open_ = unsaved_ = false;
    return robot_.end_trial();
}

Status Recorder::flush() {
    if (!dataset_) return {ErrorCode::state_error, "no dataset is open: run with --out DIR"};
    return dataset_->flush();
}

std::size_t Recorder::trials_saved() const {
    // Accepted minus lost: after flush(), exactly the trials this run made durable; before, those on their way too.
    const std::size_t lost = dataset_ ? dataset_->lost_trials() : 0;
    return trials_accepted_ > lost ? trials_accepted_ - lost : 0;
}

bool Recorder::has_trial(const std::string& id) {
    if (plan_ && !plan_->claim(id)) return true;  // another shard records it
    if (!dataset_ || !dataset_->has_trial(id)) return false;
    ++trials_skipped_;
    return true;
}

void Recorder::write_run_info(const std::vector<std::pair<std::string, std::string>>& fields) {
    if (dataset_) (void)dataset_->write_run_info(fields);
    if (dataset_ && plan_) (void)write_file_atomic(dataset_->dir() / kShardPlanFile, plan_->csv());
}

}  // namespace rollsense::runtime
