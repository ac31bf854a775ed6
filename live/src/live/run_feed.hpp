// What a run shows in the live view, as events for the EventHub: the present
// trial's samples (sensor channels, every joint's angle and current, from the
// robot's joint table), progress with an ETA, the script's step (rs.status),
// controller, e-stop and fault state, and identification results. Called on
// the script's thread (the Session's observer hooks); never blocks it beyond
// formatting a line. On the simulation, which runs far faster than real time,
// it publishes a decimated view of the latest trial: a new trial at most every
// kMinTrialGap of wall time, samples at most every kMinSampleGap.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "live/event_hub.hpp"
#include "rollsense/classifier.hpp"

namespace rollsense::runtime {
class Session;
}

namespace rollsense::live {

class RunFeed {
public:
    RunFeed(EventHub& hub, std::string script, std::string profile);

    void sampled(runtime::Session& session);
    void progress(std::size_t done, std::size_t total, const std::string& label);
    // The script's step; the state (controllers, e-stop, faults) goes with it, so
    // a change between recordings shows without waiting for the next sample.
    void status(runtime::Session& session, const std::string& step);
    void identified(const std::string& trial, const std::vector<std::string>& classes, const Prediction& p);
    // The run's end: its outcome ("done", "failed", "cancelled") and message.
    void finished(const std::string& outcome, const std::string& message, std::size_t trials_saved);

    static constexpr std::chrono::milliseconds kMinTrialGap{250};
    static constexpr std::chrono::milliseconds kMinSampleGap{4};

private:
    using Steady = std::chrono::steady_clock;
    void publish_trial(runtime::Session& session);
    void publish_state(runtime::Session& session);

    EventHub& hub_;
    std::string script_, profile_;
    Steady::time_point started_ = Steady::now();
    Steady::time_point last_trial_{}, last_sample_{}, last_progress_{};
    std::uint64_t trial_serial_ = 0;  // trials whose first sample was seen
    bool showing_ = false;            // the present trial is the one on view
    std::string state_json_;          // last published controller/e-stop/fault state
    std::size_t trials_saved_ = 0;
};

// Compact JSON pieces for the events.
std::string json_number(double v);
std::string json_numbers(const std::vector<double>& v);
std::string json_strings(const std::vector<std::string>& v);

}  // namespace rollsense::live
