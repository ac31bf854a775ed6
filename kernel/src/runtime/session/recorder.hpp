// Trials and recording, apart from any script: a trial opens (its seed and random stream derive from the run seed and
// its id), recording starts and stops, the scheduler's sample ticks read every sensor into the trial's data, and a
// saved trial goes to the dataset. Sample times come from the sample index, so identical trials record identical data
// wherever they fall in a run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/shard.hpp"

namespace rollsense::runtime {

class Clock;
class Robot;

class Recorder {
public:
    Recorder(Robot& robot, const Clock& clock, double sample_rate_hz, std::uint64_t run_seed);
    ~Recorder();

    // Open (or, resuming, reopen) the dataset trials are saved into. Without one, trials can be recorded but not saved.
    Status open_dataset(const std::filesystem::path& dir, const DatasetInfo& info, bool resume,
                        std::size_t commit_every);
    bool has_dataset() const { return dataset_ != nullptr; }
    // Each trial once durable, as its file holds it (DatasetWriter::set_on_durable); set before open_dataset.
    void on_durable(DatasetWriter::DurableObserver observer) { on_durable_ = std::move(observer); }
    // Record only one shard's trials (rollsense/shard.hpp); its plan is written with run-info.
    void set_shard(const Shard& shard) { plan_ = std::make_unique<ShardPlan>(shard); }

    Status begin_trial(TrialInfo info);
    const TrialInfo& trial() const { return trial_; }
    // Why recording cannot start now (no trial, already recording); ok if it can.
    Status can_start() const;
    Status start(double now);
    Status stop();
    bool recording() const { return recording_; }
    const TrialData& recorded() const { return data_; }
    Status save_trial();
    Status end_trial();
    // Make every saved trial durable and listed in the manifest.
    Status flush();
    // Already in the dataset (a resumed run skips it; counted as skipped), or recorded by another shard.
    bool has_trial(const std::string& id);
    // rs.random's generator: in a trial the trial's (its seed), outside one the run's (--seed): a draw between trials
    // does not shift a trial's, and none is the same for every seed.
    std::mt19937_64& trial_random() { return trial_open_ ? trial_rng_ : run_rng_; }

    // The scheduler's sampling: when the next sample is due (infinity when not recording), and taking it. A failed
    // sample ends the recording.
    double next_sample() const { return recording_ ? next_sample_ : std::numeric_limits<double>::infinity(); }
    Status sample_tick(double now);
    std::function<void()> on_sample;  // after each sample taken (Session: its options' observer)
    std::size_t max_recording_bytes = SIZE_MAX;  // held until saved: the script's memory cap bounds it too (Session)
    // The script's end: stop the sensors, keep nothing.
    void abort_recording();
    // A trial recorded and neither saved nor ended is warned of, as dropped `when`.
    void warn_unsaved(const char* when);

    // Trials this run saved, less those a failed write lost: once flush() has returned, exactly the trials this run
    // made durable (in the manifest).
    std::size_t trials_saved() const;
    std::size_t trials_skipped() const { return trials_skipped_; }
    // run-info.csv of the dataset, if one is open (best effort).
    void write_run_info(const std::vector<std::pair<std::string, std::string>>& fields);

    // A per-trial seed from the run seed and the trial id.
    static std::uint64_t trial_seed(std::uint64_t run_seed, const std::string& trial_id);

private:
    Robot& robot_;
    const Clock& clock_;
    double sample_period_;
    std::uint64_t run_seed_;
    DatasetWriter::DurableObserver on_durable_;
    std::unique_ptr<DatasetWriter> dataset_;
    std::unique_ptr<ShardPlan> plan_;  // --shard: which trials are this process's
    TrialInfo trial_;
    bool trial_open_ = false;
    TrialData data_;
    std::mt19937_64 trial_rng_, run_rng_;
    bool recording_ = false;
    bool unsaved_ = false;  // samples recorded in the open trial, neither saved nor dropped by end_trial()
    double sample_epoch_ = 0;
    std::uint64_t sample_m_ = 0;
    double next_sample_ = 0;
    std::size_t trials_accepted_ = 0;  // save_trial() calls the dataset accepted
    std::size_t trials_skipped_ = 0;
};

}  // namespace rollsense::runtime
