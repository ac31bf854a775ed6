// One run of a roll script on a robot profile: the scheduler loop on injected
// time, the control and sampling loops, recording into a dataset, the Lua
// procedure runtime, cancellation and the safe state.
//
// The loop is single-threaded. Each iteration resumes the coroutines that are
// ready, then advances the clock to the next event (control tick, sample tick,
// or a task's wake time). Control ticks read every actuator, run controllers
// and write every actuator; sample ticks (while recording) read every sensor.
#pragma once

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/digital_io.hpp"
#include "runtime/lua/sandbox.hpp"
#include "runtime/plugin/plugin_registry.hpp"
#include "runtime/profile/profile.hpp"
#include "runtime/robot/robot.hpp"
#include "runtime/session/loop_timing.hpp"
#include "runtime/session/progress.hpp"
#include "runtime/time/clock.hpp"

namespace rollsense::runtime {

struct SessionOptions {
    std::filesystem::path script;
    std::string profile = "sim";
    std::filesystem::path out_dir;            // empty: no dataset (scripts that only move)
    std::uint64_t seed = 1;
    bool resume = false;
    Settings settings;
    std::vector<std::filesystem::path> plugin_path;  // from the command line
    std::filesystem::path share_dir;
    double time_limit_s = 0;                  // run-clock budget, 0 = none
    double cleanup_limit_s = 60;              // run-clock budget for cleanup functions
    SandboxLimits sandbox;
    std::size_t commit_every = 0;             // 0: 1 on hardware, 64 in simulation
    bool progress = true;                     // a progress bar when stderr is a terminal
    std::string command_line;                 // for run-info.csv
    DigitalLines digital_lines;               // opens the profile's e-stop and trigger lines
};

struct RunSummary {
    Status status;
    std::size_t trials_saved = 0;
    std::size_t trials_skipped = 0;  // already on disk (--resume)
    double run_time_s = 0;           // on the run clock (robot time)
    double wall_time_s = 0;
    bool cancelled = false;
    std::optional<LoopTimingSummary> control_timing;  // monotonic clock only
};

enum class WaitOutcome { ready, timed_out, cancelled };

struct Task {
    lua_State* thread = nullptr;
    int ref = LUA_NOREF;       // keeps the coroutine alive
    std::string name;
    bool is_cleanup = false;
    bool finished = false;
    // What the task waits for.
    enum class Wait { none, time, joints, predicate } wait = Wait::none;
    double wake_time = 0;       // Wait::time: wake; other waits: timeout (inf = none)
    std::vector<Joint*> joints; // Wait::joints
    double tolerance = 0.5;
    int predicate_ref = LUA_NOREF;
    std::string waiting_for;    // for timeout messages
    WaitOutcome outcome = WaitOutcome::ready;
    int nargs = 0;              // values pushed for the next resume
};

class Session {
public:
    explicit Session(SessionOptions options);
    ~Session();

    // Load profile and plugins, open the dataset, run the script and its
    // cleanup, leave the hand safe. Never throws.
    RunSummary run();

    // Prepare everything run() needs without running a script (tests).
    Status prepare();
    // Run a chunk of Lua as the main task (tests and run()).
    Status run_main_chunk();

    // -------- used by the Lua bindings --------
    static Session& of(lua_State* L);
    double now() const { return clock_->now(); }
    // Round a duration to the virtual clock's grid (2^-20 s), so that time
    // differences are exact and a trial does not depend on when it started.
    double quantize(double t) const;
    Task* current_task() { return current_; }
    Robot& robot() { return *robot_; }
    const Profile& profile() const { return profile_; }
    const SessionOptions& options() const { return options_; }
    Sandbox& sandbox() { return *sandbox_; }
    PluginRegistry& registry() { return *registry_; }

    Status begin_trial(TrialInfo info);
    const TrialInfo& trial() const { return trial_; }
    bool trial_open() const { return trial_open_; }
    Status record_start();
    Status record_stop();
    bool recording() const { return recording_; }
    const TrialData& recorded() const { return data_; }
    Status save_trial();
    // Make every saved trial durable and listed in the manifest (before analysing the dataset).
    Status flush_dataset();
    Status end_trial();
    // Already in the dataset (a resumed run skips it; counted as skipped).
    bool has_trial(const std::string& id);
    std::mt19937_64& trial_random() { return trial_rng_; }

    void spawn(lua_State* L, int function_index, std::string name);
    void add_cleanup(int function_ref) { cleanup_refs_.push_back(function_ref); }
    void report_progress(std::size_t done, std::size_t total, const std::string& label);
    Status write_output_text(const std::string& name, const std::string& text);
    const std::filesystem::path& output_dir() const { return options_.out_dir; }

    // Cancel the run (Ctrl-C, e-stop, failure of a device); thread-safe flag.
    void request_cancel(const std::string& reason);

    // The error code of the last Status a binding raised as a Lua error, so a
    // script that dies of it keeps the code (limit violation, hardware fault).
    void set_raised_code(ErrorCode code) { raised_code_ = code; }
    ErrorCode take_raised_code() {
        auto c = raised_code_;
        raised_code_ = ErrorCode::ok;
        return c;
    }

    // Derive a per-trial seed from the run seed and the trial id.
    static std::uint64_t trial_seed(std::uint64_t run_seed, const std::string& trial_id);

private:
    Status open_dataset();
    Status open_safety_lines();
    // Emergency stop: checked every control period; asserted (or unreadable)
    // stops every joint at once, locks out commands and cancels the script.
    void check_estop();
    void update_trigger();
    Status loop(bool cleanup_phase);
    bool resume_task(Task& t);
    bool condition_met(Task& t);
    void check_conditions();
    Status control_tick();
    Status sample_tick();
    void fail(Status status);
    void run_cleanup();
    void release_task(Task& t);

    SessionOptions options_;
    Profile profile_;
    std::unique_ptr<PluginRegistry> registry_;
    std::unique_ptr<Robot> robot_;
    std::unique_ptr<Clock> clock_;
    std::unique_ptr<Sandbox> sandbox_;
    std::unique_ptr<DatasetWriter> dataset_;
    std::unique_ptr<Progress> progress_;

    std::vector<std::unique_ptr<Task>> tasks_;
    Task* current_ = nullptr;
    std::vector<int> cleanup_refs_;
    Status failure_;            // first failure: script error, device error, cancellation
    bool main_finished_ = false;

    double control_period_ = 0.01;
    double sample_period_ = 1 / 31.1;
    double control_epoch_ = 0;  // control ticks at epoch + k * period
    std::uint64_t control_k_ = 0;
    double next_control_ = 0;
    double last_control_ = 0;
    std::unique_ptr<LoopTiming> loop_timing_;  // monotonic clock only
    bool recording_ = false;
    double sample_epoch_ = 0;
    std::uint64_t sample_m_ = 0;
    double next_sample_ = 0;

    TrialInfo trial_;
    bool trial_open_ = false;
    TrialData data_;
    std::mt19937_64 trial_rng_;
    std::size_t trials_saved_ = 0;
    std::size_t trials_skipped_ = 0;
    std::atomic<bool> cancel_flag_{false};
    std::string cancel_reason_;
    bool prepared_ = false;
    std::unique_ptr<DigitalInput> estop_;
    std::unique_ptr<DigitalOutput> trigger_;
    double trigger_off_time_ = -1;  // run-clock time to end the current pulse, -1 = none
    bool estop_tripped_ = false;
    ErrorCode raised_code_ = ErrorCode::ok;
};

}  // namespace rollsense::runtime
