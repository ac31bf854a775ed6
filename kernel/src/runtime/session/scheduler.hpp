// The run's scheduler, single-threaded on injected time. Each iteration resumes the tasks that are ready, then
// advances the clock to the next event: a control tick (e-stop check; read every actuator, run controllers, write
// every actuator; re-check waiting tasks), a sample tick while recording, the end of a trigger pulse, or a task's
// wake time or timeout. It knows tasks only through the Task interface: nothing here depends on Lua.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "rollsense/status.hpp"
#include "runtime/session/cancellation.hpp"
#include "runtime/session/task.hpp"

namespace rollsense::runtime {

class Clock;
class LoopTiming;
class Recorder;
class Robot;
class Safety;

class Scheduler {
public:
    // `timing` (may be null) collects control-loop jitter on real clocks.
    Scheduler(Clock& clock, Robot& robot, Recorder& recorder, Safety& safety, Cancellation& cancellation,
              double control_period, LoopTiming* timing = nullptr);
    ~Scheduler();

    // The first control tick is due now (after the robot is activated).
    void start();
    // Add a task; it is first resumed in the scheduler's next pass.
    void spawn(std::unique_ptr<Task> task, TaskRole role);
    // Run until the tasks of `phase` (main or cleanup) have ended, or the run fails, or the next event falls past
    // `deadline` (run clock), which cancels with `over_deadline` as the reason. The main phase stops at the first
    // failure; the cleanup phase lets its tasks end (they see the cancellation). Tasks still alive at the end are
    // destroyed.
    Status run(TaskRole phase, double deadline, const std::string& over_deadline);

    // Tasks not yet ended (of every role).
    std::size_t live_tasks() const;

    // The task being resumed (null between resumes).
    Task* current() const { return current_; }

    // The run's first failure: a task's error, a device error, cancellation.
    void fail(Status status);
    const Status& failure() const { return failure_; }
    Status take_failure() { return std::exchange(failure_, Status{}); }
    // Cancel the run (e-stop, failure of a device, a script's request).
    void cancel(const std::string& reason);

    // Recording started at `t`: on the virtual clock the control grid is re-phased on it, so what is recorded depends
    // only on the trial, not on where it falls in the run.
    void on_recording_start(double t);
    double next_control() const { return next_control_; }

private:
    struct Slot {
        std::unique_ptr<Task> task;  // null once finished
        TaskRole role;
        Wait wait;
        WaitOutcome outcome = WaitOutcome::ready;
    };
    double now() const;
    void resume(Slot& slot);
    bool condition_met(Slot& slot);
    void check_conditions();
    Status control_tick();
    void cancel_waits();
    double next_event() const;
    std::string where_waited() const;  // " (task 'main' waited at s.lua:12)", or empty

    Clock& clock_;
    Robot& robot_;
    Recorder& recorder_;
    Safety& safety_;
    Cancellation& cancellation_;
    LoopTiming* timing_;
    std::vector<std::unique_ptr<Slot>> slots_;  // stable addresses: tasks spawn while one runs
    Task* current_ = nullptr;
    Status failure_;

    double control_period_;
    double control_epoch_ = 0;  // control ticks at epoch + k * period
    std::uint64_t control_k_ = 0;
    double next_control_ = 0;
    double last_control_ = 0;
    double instant_ = -1;            // the run time of the last task step, and how many steps it has seen
    std::uint64_t instant_steps_ = 0;
};

}  // namespace rollsense::runtime
