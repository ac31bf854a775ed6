#include "runtime/session/session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>

#include <unistd.h>

#include <atomic>
#include <exception>
#include <new>

#include "rollsense/dataset_files.hpp"
#include "rollsense/last_resort.hpp"
#include "rollsense/log.hpp"
#include "rollsense/params.hpp"
#include "rollsense/run_config.hpp"
#include "runtime/lua/api.hpp"
#include "runtime/lua/cancel_watchdog.hpp"

namespace rollsense::runtime {
namespace fs = std::filesystem;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string utc_now() {
    std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return buf;
}

double wall_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The session whose run() is on, for the crash handlers below.
std::atomic<Session*> g_running{nullptr};

int on_lua_panic(lua_State* L) {
    Session::end_in_crash(ErrorCode::script_error, "Lua panic (an error outside any protected call)",
                          lua_tostring(L, -1));  // a pointer into the state: no allocation
}

void on_terminate() {
    Session::end_in_crash(ErrorCode::plugin_error,
                          "std::terminate (an exception nobody could catch, or one thrown while stopping)", nullptr);
}

// Lua panics and std::terminate end the process through end_in_crash while a run is on.
struct CrashHandlers {
    std::terminate_handler previous = std::set_terminate(&on_terminate);
    explicit CrashHandlers(Session* session) { g_running = session; }
    ~CrashHandlers() { g_running = nullptr, std::set_terminate(previous); }
};

}  // namespace

void Session::end_in_crash(ErrorCode code, const char* what, const char* detail) noexcept {
    const int sent = run_last_resort();
    static const char msg[] = "\nrollsense: fatal error; the prepared last-resort safe state was sent\n";
    (void)!::write(STDERR_FILENO, msg, sizeof msg - 1);
    if (Session* s = g_running.exchange(nullptr)) try {
            const std::string why = std::string(what) + (detail ? std::string(": ") + detail : std::string()) +
                                    " (" + std::to_string(sent) + " last-resort actions sent)";
            log_error("kernel", why);
            if (s->recorder_ && s->recorder_->has_dataset() && ((void)s->recorder_->flush(), true))
                s->write_run_info(Status(code, why), s->wall_start_);  // flushed or not: complete trials only
        } catch (...) {}  // no heap left: the hand is safe already, run-info cannot be written
    std::fflush(stderr);
    std::_Exit(134);
}

Session::Session(SessionOptions options) : options_(std::move(options)) {}

Session::~Session() = default;

Session& Session::of(lua_State* L) { return *session_of(L); }

Status Session::prepare() {
    if (prepared_) return {};
    auto profile = load_profile(options_.profile, options_.share_dir, options_.settings, options_.sandbox);
    if (!profile) return profile_refusal(profile.status(), options_.settings);
    profile_ = std::move(*profile);

    auto search = options_.plugin_path;
    search.insert(search.end(), profile_.plugin_path.begin(), profile_.plugin_path.end());
    registry_ = std::make_unique<PluginRegistry>(PluginRegistry::default_search_path(search));
    auto robot = Robot::create(profile_, *registry_, options_.share_dir);
    if (!robot) return profile_refusal(robot.status(), options_.settings);
    robot_ = std::move(*robot);

    clock_ = make_clock(profile_.virtual_clock);
    if (!clock_->is_virtual()) loop_timing_ = std::make_unique<LoopTiming>(1.0 / profile_.control_rate_hz);
    recorder_ = std::make_unique<Recorder>(*robot_, *clock_, profile_.sample_rate_hz, options_.seed);
    if (options_.shard) recorder_->set_shard(*options_.shard);
    if (options_.on_sample) recorder_->on_sample = [this] { options_.on_sample(*this); };
    recorder_->max_recording_bytes = options_.sandbox.memory_bytes;

    std::vector<fs::path> modules;
    if (!options_.script.empty()) modules.push_back(options_.script.parent_path().empty() ? fs::path(".") : options_.script.parent_path());
    modules.push_back(options_.share_dir / "lua");
    sandbox_ = std::make_unique<Sandbox>(options_.sandbox, modules);
    lua_atpanic(sandbox_->state(), &on_lua_panic);
    sandbox_->watch_flag(&safety_.interrupt_flag(), "interrupted by Ctrl-C or a SIGTERM/SIGHUP");
    if (!clock_->is_virtual())  // five control periods; the Dynamixel Bus Watchdog's default is 500 ms
        sandbox_->watch_motion(5000.0 / profile_.control_rate_hz, [this] { return robot_->unattended_motion(); });
    scheduler_ = std::make_unique<Scheduler>(*clock_, *robot_, *recorder_, safety_, *sandbox_,
                                             clock_->quantize(1.0 / profile_.control_rate_hz), loop_timing_.get());
    open_rollsense_api(*this);

    if (!options_.out_dir.empty())
        if (auto s = open_dataset(); !s.ok()) return s;

    if (auto s = safety_.open(profile_, options_.digital_lines); !s.ok()) return s;
    if (auto s = robot_->activate(clock_->now()); !s.ok()) return s;
    scheduler_->start();
    prepared_ = true;
    return {};
}

Status Session::open_dataset() {
    DatasetInfo info;
    info.sample_rate_hz = profile_.sample_rate_hz;
    info.channels = robot_->channel_columns();
    info.channel_units = robot_->channel_units();
    info.identification_channels = profile_.identification_channels;
    info.joints = robot_->recorded_joints();
    info.profile = profile_.name;
    info.seed = options_.seed;
    info.software_version = ROLLSENSE_VERSION;
    info.run_config = options_.run_config;
    const std::size_t every = options_.commit_every != 0 ? options_.commit_every : profile_.virtual_clock ? 64 : 1;
    auto s = recorder_->open_dataset(options_.out_dir, info, options_.resume, every);
    // A shard killed before its end must still read as that shard to --resume and merge.
    if (s.ok() && options_.shard) write_run_info(Status(ErrorCode::cancelled, "has not ended (running, or killed)"), wall_start_);
    return s;
}

RunSummary Session::run() {
    RunSummary summary;
    const double wall_start = wall_start_ = wall_seconds();
    InterruptGuard interrupts(safety_.interrupt_flag());
    CrashHandlers crash_handlers(this);

    Status s = prepare();
    if (s.ok()) {
        try {
            CancelWatchdog watchdog(*sandbox_, safety_.interrupt_flag(), options_.sandbox.cancel_grace_ms,
                                    [this, wall_start](const std::string& why, ErrorCode code) { last_resort(why, code, wall_start); });
            s = run_main_chunk();
            summary.script_ended = script_ended_ = s.ok();
            if (Status cleanup = run_cleanup(); s.ok()) s = cleanup;
        } catch (const std::bad_alloc&) {  // in the kernel's own work: the last resort needs no heap,
            const int sent = run_last_resort();  // then shutdown (below) tries the ordinary safe state
            s = Status(ErrorCode::limit_violation, "out of memory (std::bad_alloc) during the run; " +
                                                       std::to_string(sent) + " last-resort actions sent");
        }
    }
    if (robot_ && !robot_->shutdown(clock_ ? clock_->now() : 0.0, /*keep_released=*/s.ok()) && s.ok())  // review: exited 0
        s = Status(ErrorCode::hardware_fault, "a device did not shut down cleanly (above): check it before the next run");
    if (recorder_ && recorder_->has_dataset()) {
        if (auto f = recorder_->flush(); !f.ok() && s.ok()) s = f;
        else if (!f.ok() && s.code() != ErrorCode::io_error) log_error("dataset", f.error().describe());  // not in s
        write_run_info(s, wall_start);
    }
    // Only a script that ran to its end has read every setting it reads (a failed
    // or interrupted one may not have reached them); declared ones were checked at once.
    for (const auto& key : options_.settings.unused())
        if (s.ok() && !options_.settings.namespace_declared(key))
            log_warning("kernel", "--set " + key + " was not used by the profile or the script (a typo?)");

    summary.status = s;
    summary.trials_saved = recorder_ ? recorder_->trials_saved() : 0;
    summary.trials_skipped = recorder_ ? recorder_->trials_skipped() : 0;
    summary.run_time_s = clock_ ? clock_->now() : 0.0;
    summary.wall_time_s = wall_seconds() - wall_start;
    summary.cancelled = s.code() == ErrorCode::cancelled;
    if (loop_timing_) summary.control_timing = loop_timing_->summary();
    return summary;
}

// On the watchdog's thread while the Lua thread is stuck inside the script (in Lua or in long C++ work, past the
// grace period): it is not in a control tick or a recorder call then, which run between resumes; the robot calls a
// binding makes are short and bounded by the devices' own timeouts. Unless it is inside a plugin call, holding the
// devices' lock, maybe mid-packet: a healthy call ends within the devices' timeouts, so the lock is awaited up to
// kDeviceWait; one stuck in C code never lets go, and the prepared last resort (whole packets, no lock) goes out
// instead. Held until the exit; the shutdown (safe state, then release) waits only on the devices' timeouts.
void Session::last_resort(const std::string& why, ErrorCode code, double wall_start) {
    constexpr auto kDeviceWait = std::chrono::seconds(1);
    log_error("kernel", why);
    std::string how = why;
    std::unique_lock<std::recursive_timed_mutex> devices;
    if (robot_) {
        devices = std::unique_lock(robot_->devices_mutex(), std::defer_lock);
        if (devices.try_lock_for(kDeviceWait)) {
            (void)robot_->shutdown(clock_ ? clock_->now() : 0.0);  // safe state, then every device released as at a normal end
        } else {
            how += "; the script's thread held the devices (stuck inside a plugin call), so the prepared "
                   "last-resort safe state went out instead (" + std::to_string(run_last_resort()) + " actions)";
            log_error("kernel", how);
        }
    }
    if (recorder_ && recorder_->has_dataset()) {
        (void)recorder_->flush();
        write_run_info(Status(code, how), wall_start);
        if (recorder_->trials_saved() + recorder_->trials_skipped() > 0) std::fputs(options_.way_on[script_ended_].c_str(), stderr);
    }
    std::fflush(stderr);
    std::_Exit(code == ErrorCode::cancelled ? 130 : 1);  // a limit the script passed is its failure, as in the hook
}

void Session::write_run_info(const Status& s, double wall_start) {
    std::error_code ec;  // the folder relative paths of command_line start from (empty: it was removed)
    const std::string working_dir = fs::current_path(ec).string();
    std::vector<std::pair<std::string, std::string>> fields{
        {"date_utc", utc_now()}, {"command_line", options_.command_line},
        {"rollsense_version", ROLLSENSE_VERSION}, {"profile", profile_.path.string()},
        {"script", options_.script.string()}, {"working_dir", working_dir}, {"seed", std::to_string(options_.seed)},
        {"status", s.ok() ? "ok" : s.error().describe().substr(0, 1 << 16)},  // a script's error text has no bound
        {"trials_saved", std::to_string(recorder_->trials_saved())},
        {"trials_skipped", std::to_string(recorder_->trials_skipped())},
        {"run_time_s", std::to_string(clock_ ? clock_->now() : 0.0)},
        {"wall_time_s", std::to_string(wall_seconds() - wall_start)},
        {"control_loop", loop_timing_ ? loop_timing_->summary().describe() : "virtual clock"}};
    if (options_.shard) fields.emplace_back("shard", options_.shard->text());
    for (const auto& name : robot_ ? robot_->device_names() : std::vector<std::string>{})  // which build drove each device
        fields.emplace_back("device." + name, robot_->find_device(name)->plugin_build());
    recorder_->write_run_info(fields);
}

Status Session::run_main_chunk() {
    if (auto s = prepare(); !s.ok()) return s;
    if (auto s = sandbox_->load_file(options_.script); !s.ok()) return s;
    lua_State* L = sandbox_->state();
    scheduler_->spawn(std::make_unique<LuaTask>(*sandbox_, L, lua_gettop(L), "main"), TaskRole::main);
    lua_pop(L, 1);
    const double deadline = options_.time_limit_s > 0 ? options_.time_limit_s : kInf;
    return scheduler_->run(TaskRole::main, deadline,
                           "the run exceeded --time-limit (" + format_number(options_.time_limit_s) + " s of run time)");
}

Status Session::spawn(lua_State* L, int function_index, std::string name) {
    if (const auto live = scheduler_->live_tasks(); live >= kMaxTasks)
        return {ErrorCode::limit_violation,
                "rs.spawn: at most " + std::to_string(kMaxTasks) + " tasks at once (" + std::to_string(live) +
                    " have not ended); let tasks end before spawning more, or loop inside one task"};
    scheduler_->spawn(std::make_unique<LuaTask>(*sandbox_, L, function_index, std::move(name)), TaskRole::background);
    return {};
}

// However the script ended, the hand stopped (Lua review: a finger spinning at a normal end moved on through the
// cleanup; the joints a script that ended released stay released), then its cleanup functions, on a fresh cancel and
// time budget. After a failed script their errors are logged and the run's status stays the script's; after one that
// succeeded, a failed cleanup (the hand perhaps not parked) is returned, the run's failure, printed by the caller.
Status Session::run_cleanup() {
    if (!sandbox_) return {};
    robot_->safe_state(now(), /*keep_released=*/scheduler_->failure().ok());
    if (scheduler_->failure().ok()) recorder_->warn_unsaved("at the script's end");  // a cancel's trial is lost as such
    recorder_->abort_recording();
    if (cleanup_refs_.empty()) return {};
    const Status main_failure = scheduler_->take_failure();
    sandbox_->clear_cancel();
    safety_.interrupt_flag().store(false);
    lua_State* L = sandbox_->state();
    // Last registered runs first, like a stack of finally blocks.
    for (auto it = cleanup_refs_.rbegin(); it != cleanup_refs_.rend(); ++it) {
        lua_rawgeti(L, LUA_REGISTRYINDEX, *it);
        scheduler_->spawn(std::make_unique<LuaTask>(*sandbox_, L, -1, "cleanup"), TaskRole::cleanup);
        lua_pop(L, 1);
    }
    const std::string over = "cleanup exceeded its time budget (" + format_number(options_.cleanup_limit_s) + " s)";
    Status cleanup = scheduler_->run(TaskRole::cleanup, now() + options_.cleanup_limit_s, over);
    // The cleanup's own failure (exit 1), not an interrupt's (130).
    if (cleanup.message().starts_with(over)) cleanup = Status(ErrorCode::limit_violation, cleanup.message());
    // A cleanup step a device refuses because the failure left it in the error state is no news.
    if (!cleanup.ok() && !main_failure.ok())
        log(cleanup.code() != ErrorCode::state_error ? LogLevel::error : LogLevel::info, "kernel",
            "cleanup stopped: " + cleanup.message());
    (void)scheduler_->take_failure();
    scheduler_->fail(main_failure.ok() ? cleanup : main_failure);
    return main_failure.ok() ? cleanup : Status{};
}

Status Session::record_start() {
    if (auto s = recorder_->can_start(); !s.ok()) return s;
    const double t = now();
    scheduler_->on_recording_start(t);
    if (auto s = recorder_->start(t); !s.ok()) return s;
    // A pulse marks the recording's start for cameras and loggers.
    if (profile_.trigger) safety_.start_trigger_pulse(t, clock_->quantize(profile_.trigger->pulse_ms / 1000.0));
    return {};
}

void Session::report_progress(std::size_t done, std::size_t total, const std::string& label) {
    if (options_.on_progress) options_.on_progress(done, total, label, now());
}

Status Session::write_output_text(const std::string& name, const std::string& text) {
    if (options_.out_dir.empty()) return {ErrorCode::state_error, "no output folder: run with --out DIR"};
    if (auto s = check_output_name(name, "rs.write_output"); !s.ok()) return s;
    // A link placed there beforehand to a pipe, a device or a socket would be written through (sandbox review).
    if (landing_of(options_.out_dir / name).written_in_place())
        return {ErrorCode::invalid_argument, "rs.write_output: " + (options_.out_dir / name).string() + " leads to a pipe, "
                                             "a device or a socket; a script writes files into the run's folder only"};
    return write_file_atomic(options_.out_dir / name, text);
}

Status Session::check_output_name(const std::string& name, const std::string& what) {
    constexpr std::size_t kMaxName = 128;
    const std::string shown = name.substr(0, 60) + (name.size() > 60 ? "..." : "");
    const bool plain = !name.empty() && name.size() <= kMaxName && name[0] != '.' &&
                       std::all_of(name.begin(), name.end(), [](char c) {
                           return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
                       });
    if (!plain)
        return {ErrorCode::invalid_argument,
                what + ": output name '" + shown + "' must be a plain file name of at most " +
                    std::to_string(kMaxName) + " letters, digits, '.', '_' or '-' (no '/', no leading '.'); " +
                    "it goes into the output folder"};
    if (is_dataset_file(name) || name == "features.csv")  // features.csv: rs.analyse writes it
        return {ErrorCode::invalid_argument,
                what + ": '" + name + "' belongs to the dataset and cannot be written by a script; choose another name"};
    return {};
}

}  // namespace rollsense::runtime
