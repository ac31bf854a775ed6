#include "runtime/session/session.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <ctime>
#include <limits>

#include "rollsense/log.hpp"
#include "rollsense/random.hpp"
#include "runtime/lua/api.hpp"

namespace rollsense::runtime {
namespace fs = std::filesystem;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGrid = 1048576.0;  // virtual clock grid: 2^20 steps per second

// Ctrl-C / SIGTERM: the first asks the run to stop (the script is cancelled,
// its cleanup runs, the hand is made safe); the third gives up at once.
std::atomic<bool>* g_interrupt_flag = nullptr;
std::atomic<int> g_interrupts{0};
extern "C" void on_interrupt(int) {
    if (g_interrupt_flag) g_interrupt_flag->store(true);
    if (g_interrupts.fetch_add(1) >= 2) {
        const char msg[] = "\nrollsense: interrupted three times, exiting without cleanup\n";
        (void)!::write(STDERR_FILENO, msg, sizeof msg - 1);
        ::_exit(130);
    }
}

std::string utc_now() {
    std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return buf;
}

double wall_seconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Session::Session(SessionOptions options) : options_(std::move(options)) {}

Session::~Session() {
    if (sandbox_) {
        for (auto& t : tasks_) release_task(*t);
    }
    if (g_interrupt_flag == &cancel_flag_) g_interrupt_flag = nullptr;
}

Session& Session::of(lua_State* L) { return *session_of(L); }

double Session::quantize(double t) const {
    if (!clock_ || !clock_->is_virtual()) return t;
    return std::round(t * kGrid) / kGrid;
}

std::uint64_t Session::trial_seed(std::uint64_t run_seed, const std::string& trial_id) {
    // FNV-1a of the id, with the offset basis this project has always used
    // (1469598103934665603, not FNV's 14695981039346656037): every recorded
    // dataset's trial seeds depend on it, so it stays.
    std::uint64_t h = 1469598103934665603ULL;
    for (unsigned char c : trial_id) {
        h ^= c;
        h *= 1099511628211ULL;
    }
    return random::splitmix64(run_seed ^ h);
}

Status Session::prepare() {
    if (prepared_) return {};
    auto profile = load_profile(options_.profile, options_.share_dir, options_.settings);
    if (!profile) return profile.status();
    profile_ = std::move(*profile);

    auto search = options_.plugin_path;
    search.insert(search.end(), profile_.plugin_path.begin(), profile_.plugin_path.end());
    registry_ = std::make_unique<PluginRegistry>(PluginRegistry::default_search_path(search));
    auto robot = Robot::create(profile_, *registry_, options_.share_dir);
    if (!robot) return robot.status();
    robot_ = std::move(*robot);

    clock_ = make_clock(profile_.virtual_clock);
    if (!clock_->is_virtual()) loop_timing_ = std::make_unique<LoopTiming>(1.0 / profile_.control_rate_hz);
    control_period_ = quantize(1.0 / profile_.control_rate_hz);
    sample_period_ = 1.0 / profile_.sample_rate_hz;

    std::vector<fs::path> modules;
    if (!options_.script.empty()) modules.push_back(options_.script.parent_path().empty() ? fs::path(".") : options_.script.parent_path());
    modules.push_back(options_.share_dir / "lua");
    sandbox_ = std::make_unique<Sandbox>(options_.sandbox, modules);
    sandbox_->watch_flag(&cancel_flag_, "interrupted (Ctrl-C)");
    open_rollsense_api(*this);

    if (!options_.out_dir.empty())
        if (auto s = open_dataset(); !s.ok()) return s;

    if (auto s = open_safety_lines(); !s.ok()) return s;
    if (auto s = robot_->activate(clock_->now()); !s.ok()) return s;
    next_control_ = clock_->now();
    prepared_ = true;
    return {};
}

Status Session::open_safety_lines() {
    const std::string file = profile_.path.string();
    if (profile_.estop) {
        DigitalLine c{profile_.estop->chip, profile_.estop->line, profile_.estop->active_low, "rollsense-estop"};
        if (!options_.digital_lines.open_input)
            return {ErrorCode::invalid_argument, file + ": safety.estop: this program cannot open digital lines; "
                                                        "run it with `rollsense run`, or remove safety.estop"};
        auto in = options_.digital_lines.open_input(c);
        if (!in) return Status(in.error()).with_context(file + ": safety.estop");
        estop_ = std::move(*in);
        auto active = estop_->is_active();
        if (!active) return Status(active.error()).with_context(file + ": safety.estop");
        if (*active)
            return {ErrorCode::cancelled, "the emergency stop (" + c.chip + " line " + std::to_string(c.line) +
                                              ") is asserted; release it before starting a run"};
    }
    if (profile_.trigger) {
        DigitalLine c{profile_.trigger->chip, profile_.trigger->line, profile_.trigger->active_low, "rollsense-trigger"};
        if (!options_.digital_lines.open_output)
            return {ErrorCode::invalid_argument, file + ": safety.trigger: this program cannot open digital lines; "
                                                          "run it with `rollsense run`, or remove safety.trigger"};
        auto out = options_.digital_lines.open_output(c, false);
        if (!out) return Status(out.error()).with_context(file + ": safety.trigger");
        trigger_ = std::move(*out);
    }
    return {};
}

void Session::check_estop() {
    if (!estop_ || estop_tripped_) return;
    auto active = estop_->is_active();
    if (active && !*active) return;
    estop_tripped_ = true;
    const std::string reason = active ? "emergency stop asserted"
                                      : "emergency stop input unreadable (" + active.error().message + ")";
    robot_->safe_state(now());  // first, within this control period
    robot_->set_commands_locked(true, reason + "; commands are refused until the run ends");
    request_cancel(reason);
}

void Session::update_trigger() {
    if (!trigger_ || trigger_off_time_ < 0 || now() < trigger_off_time_) return;
    trigger_off_time_ = -1;
    if (auto s = trigger_->set_active(false); !s.ok()) log_warning("kernel", "trigger output: " + s.message());
}

Status Session::open_dataset() {
    DatasetInfo info;
    info.sample_rate_hz = profile_.sample_rate_hz;
    info.channels = robot_->channel_columns();
    info.joints = robot_->recorded_joints();
    info.profile = profile_.name;
    info.seed = options_.seed;
    info.software_version = ROLLSENSE_VERSION;
    auto w = DatasetWriter::open(options_.out_dir, info,
                                 options_.resume ? DatasetOpenMode::resume : DatasetOpenMode::create);
    if (!w) return w.status();
    dataset_ = std::move(*w);
    std::size_t every = options_.commit_every;
    if (every == 0) every = profile_.virtual_clock ? 64 : 1;
    dataset_->set_commit_every(every);
    return {};
}

RunSummary Session::run() {
    RunSummary summary;
    const double wall_start = wall_seconds();
    g_interrupt_flag = &cancel_flag_;
    g_interrupts.store(0);
    struct sigaction sa {};
    sa.sa_handler = &on_interrupt;
    sigemptyset(&sa.sa_mask);
    struct sigaction old_int {}, old_term {};
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);

    Status s = prepare();
    if (s.ok()) {
        progress_ = std::make_unique<Progress>(options_.progress);
        s = run_main_chunk();
        run_cleanup();
        if (progress_) progress_->finish();
    }
    if (robot_) robot_->shutdown(clock_ ? clock_->now() : 0.0);
    if (dataset_) {
        if (auto f = dataset_->flush(); !f.ok() && s.ok()) s = f;
        const auto unused = options_.settings.unused();
        (void)dataset_->write_run_info({{"date_utc", utc_now()},
                                        {"command_line", options_.command_line},
                                        {"rollsense_version", ROLLSENSE_VERSION},
                                        {"profile", profile_.path.string()},
                                        {"script", options_.script.string()},
                                        {"seed", std::to_string(options_.seed)},
                                        {"status", s.ok() ? "ok" : s.error().describe()},
                                        {"trials_saved", std::to_string(trials_saved_)},
                                        {"trials_skipped", std::to_string(trials_skipped_)},
                                        {"run_time_s", std::to_string(clock_ ? clock_->now() : 0.0)},
                                        {"wall_time_s", std::to_string(wall_seconds() - wall_start)},
                                        {"control_loop", loop_timing_ ? loop_timing_->summary().describe() : "virtual clock"}});
    }
    for (const auto& key : options_.settings.unused())
        log_warning("kernel", "--set " + key + " was not used by the profile or the script (a typo?)");

    sigaction(SIGINT, &old_int, nullptr);
    sigaction(SIGTERM, &old_term, nullptr);
    g_interrupt_flag = nullptr;
    summary.status = s;
    summary.trials_saved = trials_saved_;
    summary.trials_skipped = trials_skipped_;
    summary.run_time_s = clock_ ? clock_->now() : 0.0;
    summary.wall_time_s = wall_seconds() - wall_start;
    summary.cancelled = s.code() == ErrorCode::cancelled;
    if (loop_timing_) summary.control_timing = loop_timing_->summary();
    return summary;
}

Status Session::run_main_chunk() {
    if (auto s = prepare(); !s.ok()) return s;
    if (auto s = sandbox_->load_file(options_.script); !s.ok()) return s;
    lua_State* L = sandbox_->state();
    spawn(L, lua_gettop(L), "main");
    lua_pop(L, 1);
    return loop(false);
}

void Session::spawn(lua_State* L, int function_index, std::string name) {
    lua_State* main = sandbox_->state();
    function_index = lua_absindex(L, function_index);
    auto t = std::make_unique<Task>();
    t->name = std::move(name);
    t->thread = lua_newthread(main);
    t->ref = luaL_ref(main, LUA_REGISTRYINDEX);
    lua_pushvalue(L, function_index);
    lua_xmove(L, t->thread, 1);
    sandbox_->arm(t->thread);
    t->wake_time = kInf;
    tasks_.push_back(std::move(t));
}

void Session::release_task(Task& t) {
    lua_State* main = sandbox_->state();
    if (t.predicate_ref != LUA_NOREF) luaL_unref(main, LUA_REGISTRYINDEX, t.predicate_ref);
    if (t.ref != LUA_NOREF) {
        close_thread(t.thread, main);
        luaL_unref(main, LUA_REGISTRYINDEX, t.ref);
    }
    t.predicate_ref = LUA_NOREF;
    t.ref = LUA_NOREF;
    t.finished = true;
}

void Session::fail(Status status) {
    if (status.ok()) return;
    if (failure_.ok()) failure_ = std::move(status);
}

void Session::request_cancel(const std::string& reason) {
    sandbox_->cancel(reason);
    fail(Status(ErrorCode::cancelled, reason));
}

bool Session::resume_task(Task& t) {
    lua_State* main = sandbox_->state();
    current_ = &t;
    sandbox_->start_slice();
    int nres = 0;
    const int status = lua_resume(t.thread, main, t.nargs, &nres);
    current_ = nullptr;
    t.nargs = 0;
    if (status == LUA_YIELD) {
        lua_pop(t.thread, nres);
        return true;
    }
    if (status != LUA_OK) {
        const char* msg = lua_tostring(t.thread, -1);
        std::string text = msg ? msg : "(error object is not a string)";
        luaL_traceback(main, t.thread, text.c_str(), 0);
        std::string trace = lua_tostring(main, -1);
        lua_pop(main, 1);
        ErrorCode code = take_raised_code();
        if (sandbox_->cancelled()) code = ErrorCode::cancelled;
        if (code == ErrorCode::ok) code = ErrorCode::script_error;
        fail(Status(code, "task '" + t.name + "': " + trace));
    }
    release_task(t);
    return false;
}

bool Session::condition_met(Task& t) {
    switch (t.wait) {
        case Task::Wait::none: return true;
        case Task::Wait::time: return now() >= t.wake_time;
        case Task::Wait::joints: {
            for (const Joint* j : t.joints) {
                if (j->state.moving) return false;
                const bool positional = j->command.mode != ControlMode::current && j->command.mode != ControlMode::velocity;
                if (positional && std::abs(j->state.position - j->command.position) > t.tolerance) return false;
            }
            return true;
        }
        case Task::Wait::predicate: {
            lua_State* main = sandbox_->state();
            lua_rawgeti(main, LUA_REGISTRYINDEX, t.predicate_ref);
            sandbox_->start_slice();
            if (lua_pcall(main, 0, 1, 0) != LUA_OK) {
                std::string msg = lua_tostring(main, -1);
                lua_pop(main, 1);
                fail(Status(sandbox_->cancelled() ? ErrorCode::cancelled : ErrorCode::script_error,
                            "task '" + t.name + "': wait_until condition failed: " + msg));
                t.outcome = WaitOutcome::cancelled;
                return true;
            }
            const bool met = lua_toboolean(main, -1);
            lua_pop(main, 1);
            return met;
        }
    }
    return true;
}

void Session::check_conditions() {
    for (auto& tp : tasks_) {
        Task& t = *tp;
        if (t.finished || t.wait == Task::Wait::none || t.wait == Task::Wait::time) continue;
        if (condition_met(t)) {
            if (t.outcome != WaitOutcome::cancelled) t.outcome = WaitOutcome::ready;
            t.wait = Task::Wait::none;
        } else if (now() >= t.wake_time) {
            t.outcome = WaitOutcome::timed_out;
            t.wait = Task::Wait::none;
        }
    }
}

Status Session::control_tick() {
    check_estop();
    const double t = now();
    auto s = robot_->control_tick(t, t - last_control_);
    // Real clocks only (the virtual grid is exact and re-phased per recording).
    if (loop_timing_ && control_k_ > 0) loop_timing_->add(t - last_control_, now() - t);
    last_control_ = t;
    ++control_k_;
    next_control_ = control_epoch_ + quantize(static_cast<double>(control_k_) * control_period_);
    if (!s.ok()) return s;
    check_conditions();
    return {};
}

Status Session::sample_tick() {
    const double t = now();
    auto s = robot_->sample(t, data_);
    if (!s.ok()) return s;
    // Time since the recording started, from the sample index: identical for
    // identical trials wherever they fall in a run.
    data_.time.back() = std::round(static_cast<double>(sample_m_) * sample_period_ * 1e6) / 1e6;
    ++sample_m_;
    next_sample_ = sample_epoch_ + quantize(static_cast<double>(sample_m_) * sample_period_);
    return {};
}

Status Session::loop(bool cleanup_phase) {
    const double deadline =
        cleanup_phase ? now() + options_.cleanup_limit_s
                      : (options_.time_limit_s > 0 ? options_.time_limit_s : kInf);
    for (;;) {
        if (cancel_flag_.load() && !sandbox_->cancelled()) {
            sandbox_->cancel(cleanup_phase ? "interrupted again during cleanup" : "interrupted (Ctrl-C)");
            fail(Status(ErrorCode::cancelled, sandbox_->cancel_reason()));
        }
        if (sandbox_->cancelled()) {
            for (auto& t : tasks_) {
                if (t->finished) continue;
                sandbox_->arm(t->thread);
                if (t->wait != Task::Wait::none) {
                    t->wait = Task::Wait::none;
                    t->outcome = WaitOutcome::cancelled;
                }
            }
        }
        // Resume every task that is ready; spawned tasks join at the end.
        for (std::size_t i = 0; i < tasks_.size(); ++i) {
            Task& t = *tasks_[i];
            if (t.finished) continue;
            if (t.wait == Task::Wait::time && now() >= t.wake_time) t.wait = Task::Wait::none;
            if (t.wait != Task::Wait::none && now() >= t.wake_time) {
                // A timeout that falls between control ticks: last look, then give up.
                const bool met = condition_met(t);
                if (t.outcome != WaitOutcome::cancelled) t.outcome = met ? WaitOutcome::ready : WaitOutcome::timed_out;
                t.wait = Task::Wait::none;
            }
            if (t.wait != Task::Wait::none) continue;
            resume_task(t);
            if (!failure_.ok() && !cleanup_phase) break;
        }
        bool main_alive = false;
        for (auto& t : tasks_) main_alive = main_alive || (!t->finished && (cleanup_phase ? t->is_cleanup : t->name == "main"));
        if (!main_alive || (!failure_.ok() && !cleanup_phase)) break;

        double next = next_control_;
        if (recording_) next = std::min(next, next_sample_);
        if (trigger_off_time_ >= 0) next = std::min(next, trigger_off_time_);
        for (auto& t : tasks_)
            if (!t->finished && t->wait != Task::Wait::none) next = std::min(next, t->wake_time);
        if (next > deadline) {
            const std::string why = cleanup_phase ? "cleanup exceeded its time budget (" +
                                                        std::to_string(options_.cleanup_limit_s) + " s)"
                                                  : "the run exceeded --time-limit (" +
                                                        std::to_string(options_.time_limit_s) + " s of run time)";
            sandbox_->cancel(why);
            fail(Status(ErrorCode::cancelled, why));
            if (cleanup_phase) break;
            continue;
        }
        clock_->sleep_until(next);
        update_trigger();
        if (now() >= next_control_) {
            if (auto s = control_tick(); !s.ok()) {
                fail(s);
                robot_->safe_state(now());
                sandbox_->cancel(s.message());
                if (cleanup_phase) break;
            }
        }
        if (recording_ && now() >= next_sample_) {
            if (auto s = sample_tick(); !s.ok()) {
                fail(s);
                robot_->safe_state(now());
                sandbox_->cancel(s.message());
                recording_ = false;
            }
        }
    }
    // Whatever the main task spawned ends with it.
    for (auto& t : tasks_)
        if (!t->finished) release_task(*t);
    tasks_.clear();
    return failure_;
}

void Session::run_cleanup() {
    if (!sandbox_) return;
    const bool failed = !failure_.ok();
    if (failed) {
        log_error("kernel", failure_.message());
        robot_->safe_state(now());  // stop first, then let the script tidy up
    }
    if (recording_) {
        recording_ = false;
        (void)robot_->stop_recording();
    }
    if (cleanup_refs_.empty()) return;
    const Status main_failure = failure_;
    failure_ = {};
    sandbox_->clear_cancel();
    cancel_flag_.store(false);
    lua_State* L = sandbox_->state();
    // Last registered runs first, like a stack of finally blocks.
    for (auto it = cleanup_refs_.rbegin(); it != cleanup_refs_.rend(); ++it) {
        lua_rawgeti(L, LUA_REGISTRYINDEX, *it);
        spawn(L, -1, "cleanup");
        tasks_.back()->is_cleanup = true;
        lua_pop(L, 1);
    }
    Status cleanup = loop(true);
    if (!cleanup.ok()) log_error("kernel", "cleanup: " + cleanup.message());
    failure_ = main_failure.ok() ? cleanup : main_failure;
}

// --------------------------------------------------------------- trials --

Status Session::begin_trial(TrialInfo info) {
    if (recording_) return {ErrorCode::state_error, "a trial cannot begin while recording (call rs.record_stop() first)"};
    if (info.id.empty()) return {ErrorCode::invalid_argument, "a trial needs an id"};
    info.seed = trial_seed(options_.seed, info.id);
    trial_ = std::move(info);
    trial_rng_.seed(trial_.seed);
    trial_open_ = true;
    data_ = TrialData{};
    return robot_->begin_trial(trial_);
}

Status Session::record_start() {
    if (!trial_open_) return {ErrorCode::state_error, "recording needs a trial: call rs.trial{object=..., ...} first"};
    if (recording_) return {ErrorCode::state_error, "already recording"};
    const double t = now();
    if (clock_->is_virtual()) {
        // Re-phase the control grid on the recording: what is recorded then
        // depends only on the trial, not on where it falls in the run.
        control_epoch_ = t;
        control_k_ = 1;
        next_control_ = t + control_period_;
    }
    if (auto s = robot_->start_recording(t); !s.ok()) return s;
    data_ = TrialData{};
    data_.channels.resize(robot_->channel_columns().size());
    data_.joints.resize(robot_->recorded_joints().size());
    recording_ = true;
    if (trigger_) {  // a pulse marks the recording's start for cameras and loggers
        if (auto s = trigger_->set_active(true); !s.ok()) log_warning("kernel", "trigger output: " + s.message());
        trigger_off_time_ = t + quantize(profile_.trigger->pulse_ms / 1000.0);
    }
    sample_epoch_ = t;
    sample_m_ = 0;
    next_sample_ = t;
    return {};
}

Status Session::record_stop() {
    if (!recording_) return {ErrorCode::state_error, "not recording"};
    recording_ = false;
    return robot_->stop_recording();
}

Status Session::save_trial() {
    if (!dataset_) return {ErrorCode::state_error, "no dataset is open: run with --out DIR to save trials"};
    if (recording_) return {ErrorCode::state_error, "stop recording before saving the trial"};
    if (data_.samples() == 0) return {ErrorCode::state_error, "trial '" + trial_.id + "' recorded no samples"};
    TrialRecord rec;
    rec.info = trial_;
    auto s = dataset_->add_trial(rec, data_);
    if (s.ok()) ++trials_saved_;
    return s;
}

Status Session::flush_dataset() {
    if (!dataset_) return {ErrorCode::state_error, "no dataset is open: run with --out DIR"};
    return dataset_->flush();
}

Status Session::end_trial() {
    if (recording_) (void)record_stop();
    trial_open_ = false;
    return robot_->end_trial();
}

bool Session::has_trial(const std::string& id) {
    if (!dataset_ || !dataset_->has_trial(id)) return false;
    ++trials_skipped_;
    return true;
}

void Session::report_progress(std::size_t done, std::size_t total, const std::string& label) {
    if (progress_) progress_->update(done, total, label, now());
}

Status Session::write_output_text(const std::string& name, const std::string& text) {
    if (options_.out_dir.empty()) return {ErrorCode::state_error, "no output folder: run with --out DIR"};
    if (name.empty() || name.find('/') != std::string::npos || name[0] == '.')
        return {ErrorCode::invalid_argument, "output name '" + name + "' must be a plain file name (no '/', no leading '.')"};
    if (name == "manifest.csv" || name == "dataset-info.csv" || name == "run-info.csv")
        return {ErrorCode::invalid_argument, "'" + name + "' belongs to the dataset and cannot be written by a script"};
    return write_file_atomic(options_.out_dir / name, text);
}

}  // namespace rollsense::runtime
