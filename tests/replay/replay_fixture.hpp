// Helpers for the replay tests: temporary folders, small datasets written by
// the SDK's writer or by hand, a log capture, and a configured ReplaySensor.
#pragma once

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <unistd.h>
#include <vector>

#include "replay_sensor.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/log.hpp"
#include "log_capture.hpp"
#include "temp_dir.hpp"

namespace rt {

namespace fs = std::filesystem;
using namespace rollsense;

// Replay tests' folders are named rollsense-replay-*.
class TempDir : public rollsense::testing::TempDir {
public:
    TempDir() : rollsense::testing::TempDir("rollsense-replay") {}
};
using rollsense::testing::read_file;
using rollsense::testing::write_file;

// One trial to write: its samples say where they come from, ch1 = index,
// ch2 = 100 + index, ch3 = 200 + index, the finger sweeping 0.5 deg a sample.
struct TrialSpec {
    TrialSpec(std::string object_ = "C1", std::string speed_ = "10", int repetition_ = 1, std::size_t samples_ = 50,
              double rate_hz_ = 31.1, std::uint64_t seed_ = 0, std::string id_ = {})
        : object(std::move(object_)), speed(std::move(speed_)), repetition(repetition_), samples(samples_),
          rate_hz(rate_hz_), seed(seed_), id(std::move(id_)) {}
    std::string object;
    std::string speed;
    int repetition;
    std::size_t samples;
    double rate_hz;
    std::uint64_t seed;  // 0: not recorded
    std::string id;      // empty: "<object>-v<speed>-r<rep>"
};

inline std::string trial_id(const TrialSpec& t) {
    if (!t.id.empty()) return t.id;
    char rep[16];
    std::snprintf(rep, sizeof rep, "%03d", t.repetition);
    return t.object + "-v" + t.speed + "-r" + rep;
}

inline double sweep_angle(std::size_t i) { return -44.0 + 0.5 * static_cast<double>(i); }

inline TrialData trial_data(const TrialSpec& t) {
    TrialData d;
    d.channels.resize(3);
    d.joints.resize(1);
    for (std::size_t i = 0; i < t.samples; ++i) {
        // The session's own rounding: time from the index, to 1 µs.
        d.time.push_back(std::round(static_cast<double>(i) / t.rate_hz * 1e6) / 1e6);
        for (std::size_t c = 0; c < 3; ++c) d.channels[c].push_back(100.0 * static_cast<double>(c) + static_cast<double>(i));
        d.joints[0].push_back(sweep_angle(i));
        d.valid.push_back(1);
    }
    return d;
}

// A dataset written by the SDK's writer, as a recording run writes it.
inline void write_dataset(const fs::path& dir, const std::vector<TrialSpec>& trials, std::uint64_t seed = 7,
                          double rate_hz = 31.1) {
    DatasetInfo info;
    info.sample_rate_hz = rate_hz;
    info.channels = {"ch1", "ch2", "ch3"};
    info.joints = {"sensing_finger"};
    info.profile = "test";
    info.seed = seed;
    auto w = DatasetWriter::open(dir, info, DatasetOpenMode::create);
    if (!w) throw StatusError(w.status());
    for (const auto& t : trials) {
        TrialRecord r;
        r.info.id = trial_id(t);
        r.info.object = t.object;
        r.info.speed = t.speed;
        r.info.repetition = t.repetition;
        r.info.seed = t.seed;
        throw_if_error((*w)->add_trial(r, trial_data(t)));
    }
    throw_if_error((*w)->flush());
}

using rollsense::testing::LogCapture;

inline Result<ParamSet> replay_params(const fs::path& dataset, std::map<std::string, ParamValue> extra = {}) {
    extra["dataset"] = dataset.string();
    return validate_params(plugins::replay::replay_schema(), extra, "test");
}

// A ReplaySensor configured and active on `dataset`.
inline Result<std::unique_ptr<plugins::replay::ReplaySensor>> open_replay(const fs::path& dataset,
                                                                          std::map<std::string, ParamValue> extra = {}) {
    auto params = replay_params(dataset, std::move(extra));
    if (!params) return params.error();
    auto s = std::make_unique<plugins::replay::ReplaySensor>();
    PluginContext ctx;
    ctx.instance = "tactile";
    ctx.virtual_time = true;
    if (auto st = s->on_configure(*params, ctx); !st.ok()) return st.error();
    if (auto st = s->on_activate(); !st.ok()) return st.error();
    return s;
}

inline TrialInfo script_trial(const std::string& object, const std::string& speed, int repetition,
                              std::uint64_t seed = 0) {
    TrialInfo t;
    t.object = object;
    t.speed = speed;
    t.repetition = repetition;
    t.id = trial_id(TrialSpec(object, speed, repetition));
    t.seed = seed;
    return t;
}

// Drives a sensor like the kernel's sampling loop on the virtual clock: start
// at `t0`, sample m at t0 + m/rate quantised to 2^-20 s; the finger at
// `angle(m)`.
struct Driver {
    std::vector<std::string> joint_names{"sensing_finger"};
    std::vector<JointState> joint_states{JointState{}};
    double t0 = 12.5;
    double rate_hz = 31.1;

    static double quantize(double t) { return std::round(t * 1048576.0) / 1048576.0; }

    SampleInput input(double time, double angle) {
        joint_states[0].position = angle;
        return SampleInput{time, &joint_names, &joint_states};
    }
    double time_of(std::size_t m) const { return t0 + quantize(static_cast<double>(m) / rate_hz); }

    // Record `n` frames; throws on a Status error.
    std::vector<Frame> record(Sensor& s, std::size_t n, const std::function<double(std::size_t)>& angle = sweep_angle) {
        throw_if_error(s.start_recording(input(t0, angle(0))));
        std::vector<Frame> frames;
        for (std::size_t m = 0; m < n; ++m) {
            Frame f;
            f.time = time_of(m);
            f.values.assign(s.channels().size(), 0.0);
            throw_if_error(s.read(input(f.time, angle(m)), f));
            frames.push_back(std::move(f));
        }
        throw_if_error(s.stop_recording());
        return frames;
    }
};

}  // namespace rt
