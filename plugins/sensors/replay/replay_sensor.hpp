// The `replay` sensor plugin: plays a recorded dataset back through the same
// scripts that recorded it (docs/replay.md).
//
// Configure opens the dataset (dataset-info.csv, manifest.csv; every trial file
// listed must exist) but reads no trial file: each trial is loaded when the
// script begins it and dropped when the trial ends, so a dataset of any size
// streams. The trial played is chosen by the script: the one matching its
// rs.trial{...} (select = "match"), the next one in manifest order
// (select = "order"), or one pinned with device:call("select", {...}).
//
// While recording, each read serves the recorded sample at that moment of the
// playback (playback.hpp), and compares the hand's joint (check_joint) with the
// angle the recording holds there: a script whose roll does not match the
// recording's is warned about (or its frames marked invalid). A read after the
// recording's end is an invalid frame saying so (or holds the last sample,
// past_end = "hold"); a sample recorded as invalid or NaN replays as invalid.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "playback.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/sensor.hpp"
#include "trial_selection.hpp"

namespace rollsense::plugins::replay {

ParamSchema replay_schema();

class ReplaySensor final : public Sensor {
public:
    Status on_configure(const ParamSet& params, const PluginContext& context) override;
    Status on_cleanup() override;
    Status on_recover() override;
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args) override;

    std::vector<ChannelInfo> channels() const override { return channels_; }
    Status begin_trial(const TrialInfo& trial) override;
    Status start_recording(const SampleInput& input) override;
    Status read(const SampleInput& input, Frame& out) override;
    Status stop_recording() override;
    Status end_trial() override;

private:
    enum class Select { match, order };
    enum class PastEnd { invalid, hold };
    enum class OnMismatch { warn, invalid };

    // One trial in play.
    struct Current {
        std::size_t index = 0;  // in the manifest
        TrialData data;
        Playback playback;
        bool recording = false;
        std::size_t mismatches = 0;
        double max_angle_error = 0.0;
    };

    std::string source() const;
    std::string dataset_name() const;
    // "--set devices.INSTANCE.params.PARAM", as a message's way out spells it.
    std::string setting(const std::string& param) const;
    // check_column_ for check_joint_, or why the dataset has none to check.
    Status find_check_column(const std::filesystem::path& dir);
    Result<std::size_t> choose(const TrialInfo& trial);
    void check_roll(const SampleInput& input, std::size_t index, Frame& out);
    ValueMap describe(std::size_t index) const;
    Result<ValueMap> select(const ValueMap& args);
    ValueMap status_map() const;
    void reset_trial_state();

    // parameters
    std::string dataset_param_;
    Select select_ = Select::match;
    PastEnd past_end_ = PastEnd::invalid;
    OnMismatch on_mismatch_ = OnMismatch::warn;
    std::string check_joint_;
    double angle_tolerance_ = 2.0;
    std::string instance_;

    std::optional<DatasetReader> dataset_;
    std::vector<ChannelInfo> channels_;
    std::optional<std::size_t> check_column_;  // recorded joint column of check_joint
    std::optional<TrialQuery> pinned_;         // device:call("select", ...) for the next trial
    std::size_t next_in_order_ = 0;
    std::optional<Current> current_;
    bool seed_warned_ = false;
    bool joint_missing_warned_ = false;
    std::size_t seed_mismatches_ = 0;
    std::size_t trials_played_ = 0;
};

}  // namespace rollsense::plugins::replay
