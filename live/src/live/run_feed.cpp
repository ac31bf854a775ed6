#include "live/run_feed.hpp"

#include <charconv>
#include <cmath>

#include "analysis/learn/json_writer.hpp"
#include "runtime/session/session.hpp"

namespace rollsense::live {

using learn::json_quote;

std::string json_number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

std::string json_numbers(const std::vector<double>& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + json_number(v[i]);
    return s + "]";
}

std::string json_strings(const std::vector<std::string>& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + json_quote(v[i]);
    return s + "]";
}

RunFeed::RunFeed(EventHub& hub, std::string script, std::string profile)
    : hub_(hub), script_(std::move(script)), profile_(std::move(profile)) {
    hub_.publish_state("run", sse_event("run", "{\"script\":" + json_quote(script_) + ",\"profile\":" +
                                                  json_quote(profile_) + ",\"outcome\":\"running\"}"));
}

void RunFeed::publish_trial(runtime::Session& session) {
    const auto& robot = session.robot();
    const auto& t = session.trial();
    std::vector<std::string> joints, joint_units;
    for (const auto& j : robot.joints()) {
        joints.push_back(j.name);
        joint_units.push_back(j.info.unit);  // fingers in deg, the palm and the winch in mm
    }
    std::string json = "{\"id\":" + json_quote(t.id) + ",\"object\":" + json_quote(t.object) +
                       ",\"speed\":" + json_quote(t.speed) + ",\"repetition\":" + std::to_string(t.repetition) +
                       ",\"serial\":" + std::to_string(trial_serial_) +
                       ",\"channels\":" + json_strings(robot.channel_columns()) +
                       ",\"channel_units\":" + json_strings(robot.channel_units()) +
                       ",\"joints\":" + json_strings(joints) + ",\"joint_units\":" + json_strings(joint_units) +
                       ",\"current_unit\":\"mA\"}";
    hub_.publish_state("trial", sse_event("trial", json));
}

void RunFeed::publish_state(runtime::Session& session) {
    const auto& robot = session.robot();
    std::string faults = "[";
    const auto fault = [&](const std::string& device, const std::string& joint, const std::string& reason) {
        faults += (faults.size() > 1 ? "," : "") + std::string("{\"device\":") + json_quote(device) +
                  ",\"joint\":" + json_quote(joint) + ",\"reason\":" + json_quote(reason) + "}";
    };
    std::string modes = "{";
    const runtime::ActuatorHandle* last_device = nullptr;
    for (const auto& j : robot.joints()) {
        const std::string device = j.actuator ? j.actuator->instance() : "";
        if (!j.state.fault.empty()) fault(device, j.name, j.state.fault);
        if (j.actuator && j.actuator != last_device && j.actuator->state() == LifecycleState::error)
            fault(device, "", j.actuator->last_error().message());
        last_device = j.actuator;
        modes += (modes.size() > 1 ? "," : "") + json_quote(j.name) + ":" +
                 json_quote(std::string(to_string(j.state.mode)) + (j.state.torque_enabled ? "" : ", torque off"));
    }
    std::string controllers = "{";
    for (const auto& c : session.profile().controllers)
        controllers += (controllers.size() > 1 ? "," : "") + json_quote(c.name) + ":" +
                       (robot.controller_enabled(c.name) ? "true" : "false");
    const std::string estop = robot.commands_locked_reason();
    std::string json = "{\"estop\":" + (estop.empty() ? std::string("null") : json_quote(estop)) +
                       ",\"faults\":" + faults + "],\"modes\":" + modes + "},\"controllers\":" + controllers + "}}";
    if (json == state_json_) return;
    state_json_ = json;
    hub_.publish_state("state", sse_event("state", json));
}

void RunFeed::sampled(runtime::Session& session) {
    const auto& data = session.recorded();
    const auto now = Steady::now();
    if (data.samples() == 1) {  // a new recording
        ++trial_serial_;
        showing_ = now - last_trial_ >= kMinTrialGap;
        if (showing_) {
            last_trial_ = now;
            publish_trial(session);
        }
    }
    if (!showing_ || now - last_sample_ < kMinSampleGap) return;
    last_sample_ = now;
    publish_state(session);
    std::vector<double> channels, angles, currents;
    for (const auto& c : data.channels) channels.push_back(c.back());
    for (const auto& j : session.robot().joints()) {
        angles.push_back(j.state.position);
        currents.push_back(j.state.current);
    }
    hub_.publish(sse_event("sample", "{\"serial\":" + std::to_string(trial_serial_) + ",\"n\":" +
                                         std::to_string(data.samples()) + ",\"t\":" + json_number(data.time.back()) +
                                         ",\"valid\":" + (data.valid.back() ? "true" : "false") +
                                         ",\"c\":" + json_numbers(channels) + ",\"a\":" + json_numbers(angles) +
                                         ",\"i\":" + json_numbers(currents) + "}"));
}

void RunFeed::progress(std::size_t done, std::size_t total, const std::string& label) {
    const auto now = Steady::now();
    if (done != total && now - last_progress_ < kMinTrialGap) return;
    last_progress_ = now;
    // ETA from the pace so far (wall time): the live view runs alongside the
    // hand, where wall time is the robot's time.
    const double elapsed = std::chrono::duration<double>(now - started_).count();
    const double eta = done > 0 && total >= done ? elapsed / static_cast<double>(done) * static_cast<double>(total - done)
                                                 : std::nan("");
    hub_.publish_state("progress", sse_event("progress", "{\"done\":" + std::to_string(done) + ",\"total\":" +
                                                             std::to_string(total) + ",\"label\":" + json_quote(label) +
                                                             ",\"elapsed_s\":" + json_number(elapsed) +
                                                             ",\"eta_s\":" + json_number(eta) + ",\"dropped\":" +
                                                             std::to_string(hub_.dropped()) + "}"));
}

void RunFeed::status(runtime::Session& session, const std::string& step) {
    hub_.publish_state("status", sse_event("status", "{\"step\":" + json_quote(step) + "}"));
    publish_state(session);
}

void RunFeed::identified(const std::string& trial, const std::vector<std::string>& classes, const Prediction& p) {
    std::string scores = "{";
    for (std::size_t i = 0; i < classes.size() && i < p.scores.size(); ++i)
        scores += (i ? "," : "") + json_quote(classes[i]) + ":" + json_number(p.scores[i]);
    hub_.publish_state("result", sse_event("result", "{\"trial\":" + json_quote(trial) + ",\"object\":" +
                                                         json_quote(p.class_name) + ",\"scores\":" + scores + "}}"));
}

void RunFeed::finished(const std::string& outcome, const std::string& message, std::size_t trials_saved) {
    trials_saved_ = trials_saved;
    hub_.publish_state("run", sse_event("run", "{\"script\":" + json_quote(script_) + ",\"profile\":" +
                                                  json_quote(profile_) + ",\"outcome\":" + json_quote(outcome) +
                                                  ",\"message\":" + json_quote(message) + ",\"trials_saved\":" +
                                                  std::to_string(trials_saved) + ",\"dropped\":" +
                                                  std::to_string(hub_.dropped()) + "}"));
}

}  // namespace rollsense::live
