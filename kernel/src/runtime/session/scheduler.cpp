#include "runtime/session/scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "runtime/robot/robot.hpp"
#include "runtime/session/loop_timing.hpp"
#include "runtime/session/recorder.hpp"
#include "runtime/session/safety.hpp"
#include "runtime/time/clock.hpp"

namespace rollsense::runtime {

Scheduler::Scheduler(Clock& clock, Robot& robot, Recorder& recorder, Safety& safety, Cancellation& cancellation,
                     double control_period, LoopTiming* timing)
    : clock_(clock),
      robot_(robot),
      recorder_(recorder),
      safety_(safety),
      cancellation_(cancellation),
      timing_(timing),
      control_period_(control_period) {}

Scheduler::~Scheduler() = default;

double Scheduler::now() const { return clock_.now(); }

void Scheduler::start() { next_control_ = now(); }

void Scheduler::spawn(std::unique_ptr<Task> task, TaskRole role) {
    auto slot = std::make_unique<Slot>();
    slot->task = std::move(task);
    slot->role = role;
    slots_.push_back(std::move(slot));
}

std::size_t Scheduler::live_tasks() const {
    return static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(), [](const auto& s) { return s->task != nullptr; }));
}

void Scheduler::fail(Status status) {
    if (status.ok()) return;
    if (failure_.ok()) failure_ = std::move(status);
}

// Ctrl-C, --time-limit, the e-stop and a fault the control loop finds (a device's, a joint past its limit) name no
// place in the script: the first task that waits says where, so a wait that could never end is found.
std::string Scheduler::where_waited() const {
    for (const auto& s : slots_)
        if (const std::string line = s->task && s->wait.kind != Wait::Kind::none ? s->task->where() : ""; !line.empty())
            return " (task '" + s->task->name() + "' waited at " + line + ")";
    return {};
}

void Scheduler::cancel(const std::string& reason) {
    cancellation_.cancel(reason);
    fail(Status(ErrorCode::cancelled, reason + where_waited()));
}

void Scheduler::on_recording_start(double t) {
    if (!clock_.is_virtual()) return;
    control_epoch_ = t;
    control_k_ = 1;
    next_control_ = t + control_period_;
}

void Scheduler::resume(Slot& slot) {
    // Sandbox review: a chain of rs.spawn kept a task ready at every pass: the virtual clock and --time-limit stood still.
    if (now() != instant_) instant_ = now(), instant_steps_ = 0;
    if (++instant_steps_ == 100'000) {  // once: the cancel then ends every task at its next instruction
        const std::string why = "100000 task steps at run time " + format_number(now()) + " s without the clock moving "
                                "(a chain of rs.spawn?); let tasks wait (rs.wait)";
        fail(Status(ErrorCode::limit_violation, why));
        cancellation_.cancel(why);
    }
    current_ = slot.task.get();
    TaskStep step = slot.task->resume(slot.outcome);
    current_ = nullptr;
    if (!step.finished) {
        slot.wait = std::move(step.wait);
        slot.outcome = WaitOutcome::ready;
        return;
    }
    if (!step.error.ok())
        fail(Status(step.error.code(), "task '" + slot.task->name() + "': " + step.error.message()));
    slot.task.reset();
}

bool Scheduler::condition_met(Slot& slot) {
    const Wait& w = slot.wait;
    switch (w.kind) {
        case Wait::Kind::none: return true;
        case Wait::Kind::time: return now() >= w.until;
        case Wait::Kind::joints:
            for (const Joint* j : w.joints) {
                if (j->state.moving) return false;
                const bool positional = j->command.mode != ControlMode::current && j->command.mode != ControlMode::velocity;
                if (positional && std::abs(j->state.position - j->command.position) > w.tolerance) return false;
            }
            return true;
        case Wait::Kind::predicate: {
            auto met = w.predicate();
            if (!met) {
                fail(Status(met.status().code(), "task '" + slot.task->name() + "': " + met.status().message()));
                slot.outcome = WaitOutcome::cancelled;
                return true;
            }
            return *met;
        }
    }
    return true;
}

// After a control tick: joint and predicate waits that are met, or timed out.
void Scheduler::check_conditions() {
    for (auto& sp : slots_) {
        Slot& s = *sp;
        if (!s.task || s.wait.kind == Wait::Kind::none || s.wait.kind == Wait::Kind::time) continue;
        if (condition_met(s)) {
            if (s.outcome != WaitOutcome::cancelled) s.outcome = WaitOutcome::ready;
            s.wait = Wait{};
        } else if (now() >= s.wait.until) {
            s.outcome = WaitOutcome::timed_out;
            s.wait = Wait{};
        }
    }
}

// Cancelled: every live task hears of it, and every wait ends as cancelled.
void Scheduler::cancel_waits() {
    for (auto& s : slots_)
        if (s->task) {
            s->task->on_cancel();
            if (s->wait.kind != Wait::Kind::none) s->wait = Wait{}, s->outcome = WaitOutcome::cancelled;
        }
}

Status Scheduler::control_tick() {
    if (auto reason = safety_.check_estop(robot_, now())) cancel(*reason);
    const double t = now();
    auto s = robot_.control_tick(t, t - last_control_);
    // Real clocks only (the virtual grid is exact and re-phased per recording).
    if (timing_ && control_k_ > 0) timing_->add(t - last_control_, now() - t);
    last_control_ = t;
    ++control_k_;
    next_control_ = control_epoch_ + clock_.quantize(static_cast<double>(control_k_) * control_period_);
    if (!s.ok()) return s;
    check_conditions();
    return {};
}

double Scheduler::next_event() const {
    double next = std::min({next_control_, recorder_.next_sample(), safety_.next_event()});
    for (const auto& s : slots_)
        if (s->task) next = std::min(next, s->wait.kind == Wait::Kind::none ? now() : s->wait.until);
    return next;
}

Status Scheduler::run(TaskRole phase, double deadline, const std::string& over_deadline) {
    const bool cleanup = phase == TaskRole::cleanup;
    for (;;) {
        if (safety_.interrupt_flag().load() && !cancellation_.cancelled())
            cancel(cleanup ? "interrupted again during cleanup" : "interrupted by Ctrl-C or a SIGTERM/SIGHUP");
        if (cancellation_.cancelled()) cancel_waits();
        // Ended tasks leave their slots: a script that spawns short tasks for hours does not grow this list.
        slots_.erase(std::remove_if(slots_.begin(), slots_.end(), [](const auto& s) { return !s->task; }), slots_.end());
        // Resume every task that is ready; one spawned in this pass starts in the next, at the same instant but after
        // the checks above (review: a chain of spawns kept this loop going past Ctrl-C and the control period).
        for (std::size_t i = 0, ready = slots_.size(); i < ready; ++i) {
            Slot& s = *slots_[i];
            if (!s.task) continue;
            if (s.wait.kind == Wait::Kind::time && now() >= s.wait.until) s.wait = Wait{};
            if (s.wait.kind != Wait::Kind::none && now() >= s.wait.until) {
                // A timeout that falls between control ticks: last look, then give up.
                const bool met = condition_met(s);
                if (s.outcome != WaitOutcome::cancelled) s.outcome = met ? WaitOutcome::ready : WaitOutcome::timed_out;
                s.wait = Wait{};
            }
            if (s.wait.kind != Wait::Kind::none) continue;
            resume(s);
            if (!failure_.ok() && !cleanup) break;
        }
        const bool alive = std::any_of(slots_.begin(), slots_.end(),
                                       [&](const auto& s) { return s->task && s->role == phase; });
        if (!alive || (!failure_.ok() && !cleanup)) break;

        const double next = next_event();
        if (next > deadline) {
            cancel(over_deadline);
            if (cleanup) break;
            continue;
        }
        clock_.sleep_until(next);
        safety_.update_trigger(now());
        if (now() >= next_control_) {
            if (auto s = control_tick(); !s.ok()) {
                fail(Status(s.code(), s.message() + where_waited()));
                robot_.safe_state(now());
                cancellation_.cancel(s.message());
                if (cleanup) break;
            }
        }
        if (recorder_.recording() && now() >= recorder_.next_sample()) {
            if (auto s = recorder_.sample_tick(now()); !s.ok()) {
                fail(Status(s.code(), s.message() + where_waited()));
                robot_.safe_state(now());
                cancellation_.cancel(s.message());
            }
        }
    }
    // Whatever the phase's tasks spawned ends with them.
    slots_.clear();
    return failure_;
}

}  // namespace rollsense::runtime
