// One run of a roll script on a robot profile: the assembly of the parts a run needs, in the order it needs them. The
// profile's robot (plugins), the injected clock, the recorder (trials, dataset), the safety lines, the Lua sandbox with
// the rollsense module, and the scheduler that runs the script's coroutines as tasks, then its cleanup functions, and
// leaves the hand safe. The scheduler, recorder and safety know nothing of Lua (see scheduler.hpp); this class and
// runtime/lua/ are the layer that drives them from a script.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/dataset.hpp"
#include "rollsense/digital_io.hpp"
#include "runtime/lua/lua_task.hpp"
#include "runtime/lua/sandbox.hpp"
#include "runtime/plugin/plugin_registry.hpp"
#include "runtime/profile/profile.hpp"
#include "runtime/robot/robot.hpp"
#include "runtime/session/loop_timing.hpp"
#include "runtime/session/recorder.hpp"
#include "runtime/session/safety.hpp"
#include "runtime/session/scheduler.hpp"
#include "runtime/time/clock.hpp"

namespace rollsense::runtime {

class Session;

struct SessionOptions {
    std::filesystem::path script;
    std::string profile = "sim";
    std::filesystem::path out_dir;            // empty: no dataset (scripts that only move)
    std::uint64_t seed = 1;
    bool resume = false;
    std::optional<Shard> shard;               // --shard K/N: record only this shard's trials
    Settings settings;
    std::vector<std::filesystem::path> plugin_path;  // from the command line
    std::filesystem::path share_dir;
    double time_limit_s = 0;                  // run-clock budget, 0 = none
    double cleanup_limit_s = 60;              // run-clock budget for cleanup functions
    SandboxLimits sandbox;
    std::size_t commit_every = 0;             // 0: 1 on hardware, 64 in simulation
    std::string command_line;                 // for run-info.csv
    std::array<std::string, 2> way_on;  // the watchdog's way out prints it when trials are on disk: [script ended]
    RunConfig run_config;                     // for run-config.csv; --resume refuses another
    DigitalLines digital_lines;               // opens the profile's e-stop and trigger lines
    // Observers (the live view, the progress bar): after each recorded sample and each rs.progress, on the script's
    // thread; must not block.
    std::function<void(Session&)> on_sample;
    std::function<void(std::size_t done, std::size_t total, const std::string& label, double run_clock_s)> on_progress;
};

struct RunSummary {
    Status status;
    std::size_t trials_saved = 0;
    std::size_t trials_skipped = 0;  // already on disk (--resume)
    double run_time_s = 0;           // on the run clock (robot time)
    double wall_time_s = 0;
    bool cancelled = false;
    bool script_ended = false;  // its main chunk ran to its end: a failure after it (cleanup, shutdown) needs no resume
    std::optional<LoopTimingSummary> control_timing;  // monotonic clock only
};

class Session {
public:
    explicit Session(SessionOptions options);
    ~Session();

    // Load profile and plugins, open the dataset, run the script and its cleanup, leave the hand safe. Never throws.
    RunSummary run();

    // Prepare everything run() needs without running a script (tests).
    Status prepare();
    // Run a chunk of Lua as the main task (tests and run()).
    Status run_main_chunk();

    // -------- used by the Lua bindings --------
    static Session& of(lua_State* L);
    // After a Lua panic or std::terminate in a run: the prepared last resort (no heap, no Lua), then run-info if the
    // heap still serves; exit 134.
    [[noreturn]] static void end_in_crash(ErrorCode code, const char* what, const char* detail) noexcept;
    double now() const { return clock_->now(); }
    // Round a duration to the virtual clock's grid (Clock::quantize).
    double quantize(double t) const { return clock_ ? clock_->quantize(t) : t; }
    Scheduler& scheduler() { return *scheduler_; }
    Recorder& recorder() { return *recorder_; }
    Robot& robot() { return *robot_; }
    const Profile& profile() const { return profile_; }
    const std::atomic<bool>& interrupt_flag() { return safety_.interrupt_flag(); }  // Ctrl-C, for long C++ work
    const SessionOptions& options() const { return options_; }
    Settings& settings() { return options_.settings; }  // rs.settings declares into it
    Sandbox& sandbox() { return *sandbox_; }
    PluginRegistry& registry() { return *registry_; }

    // Trials: the recorder's, plus what a recording means for the scheduler (control grid re-phased) and the safety
    // lines (trigger pulse).
    Status begin_trial(TrialInfo info) { return recorder_->begin_trial(std::move(info)); }
    const TrialInfo& trial() const { return recorder_->trial(); }
    Status record_start();
    Status record_stop() { return recorder_->stop(); }
    bool recording() const { return recorder_->recording(); }
    const TrialData& recorded() const { return recorder_->recorded(); }
    Status save_trial() { return recorder_->save_trial(); }
    // Make every saved trial durable and listed in the manifest (before analysing the dataset).
    Status flush_dataset() { return recorder_->flush(); }
    Status end_trial() { return recorder_->end_trial(); }
    // Already in the dataset (a resumed run skips it; counted as skipped).
    bool has_trial(const std::string& id) { return recorder_->has_trial(id); }
    std::mt19937_64& trial_random() { return recorder_->trial_random(); }

    // A concurrent task running the Lua function at `function_index` of L; refused past kMaxTasks tasks alive at once.
    static constexpr std::size_t kMaxTasks = 1000;
    Status spawn(lua_State* L, int function_index, std::string name);
    void add_cleanup(int function_ref) { cleanup_refs_.push_back(function_ref); }
    void report_progress(std::size_t done, std::size_t total, const std::string& label);
    Status write_output_text(const std::string& name, const std::string& text);
    // A file name a script may write into the output folder: a plain name (letters, digits, '.', '_', '-'; no leading
    // '.'; at most 128 bytes), not one of the dataset's own files (rollsense/dataset_files.hpp) nor features.csv.
    // `what` names the caller.
    static Status check_output_name(const std::string& name, const std::string& what);
    const std::filesystem::path& output_dir() const { return options_.out_dir; }

    // The last Status a binding raised as a Lua error: a script that dies of it (its text in the error's) keeps its code
    // (limit violation, hardware fault); not one that dies of another error after a pcall caught it (diff review).
    void set_raised(Status status) { raised_ = std::move(status); }
    ErrorCode take_raised_code(const std::string& error_text) {
        const bool carried = !raised_.message().empty() && error_text.find(raised_.message()) != std::string::npos;
        const auto code = carried ? raised_.code() : ErrorCode::ok;
        raised_ = {};
        return code;
    }

    // Derive a per-trial seed from the run seed and the trial id.
    static std::uint64_t trial_seed(std::uint64_t run_seed, const std::string& trial_id) {
        return Recorder::trial_seed(run_seed, trial_id);
    }

private:
    Status open_dataset();
    Status run_cleanup();
    void write_run_info(const Status& status, double wall_start);
    // The cancel watchdog's way out (its own thread): safe state (the prepared last resort if the script's thread holds
    // the devices), run-info, exit 130.
    [[noreturn]] void last_resort(const std::string& why, ErrorCode code, double wall_start);
    double wall_start_ = 0.0;  // of the current run(), for run-info on the way out

    // Declared in the order they depend on each other: the scheduler (whose Lua tasks hold references into the sandbox)
    // goes first, the robot last.
    SessionOptions options_;
    Profile profile_;
    std::unique_ptr<PluginRegistry> registry_;
    std::unique_ptr<Robot> robot_;
    std::unique_ptr<Clock> clock_;
    std::unique_ptr<LoopTiming> loop_timing_;  // monotonic clock only
    Safety safety_;
    std::unique_ptr<Recorder> recorder_;
    std::unique_ptr<Sandbox> sandbox_;
    std::unique_ptr<Scheduler> scheduler_;
    std::vector<int> cleanup_refs_;
    bool prepared_ = false;
    std::atomic<bool> script_ended_{false};  // RunSummary::script_ended, for the watchdog thread's way out
    Status raised_;
};

}  // namespace rollsense::runtime
