// A task of the scheduler: a procedure that runs in steps on the run clock. Each resume runs it until it finishes or
// asks to wait (for a time, for joints to arrive, for a condition); the scheduler resumes it again once the wait ends,
// and says how it ended (ready, timed out, cancelled). Roll scripts are tasks through the Lua layer
// (runtime/lua/lua_task.hpp); C++ procedures and tests implement the interface directly.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::runtime {

struct Joint;

enum class WaitOutcome { ready, timed_out, cancelled };

// What a task waits for. `until` is the wake time of a time wait and the timeout of the others (infinity: none).
struct Wait {
    enum class Kind { none, time, joints, predicate } kind = Kind::none;
    double until = std::numeric_limits<double>::infinity();
    std::vector<const Joint*> joints;  // Kind::joints: each not moving and within
    double tolerance = 0.5;            //   tolerance of its goal (position modes)
    // Kind::predicate: checked once per control period. An error ends the wait as cancelled and fails the run with that
    // error.
    std::function<Result<bool>()> predicate;
    std::string what;  // "joint 'finger' to reach 3.000 deg", for timeout messages

    static Wait for_time(double wake) {
        Wait w;
        w.kind = Kind::time;
        w.until = wake;
        return w;
    }
};

// The result of one resume.
struct TaskStep {
    bool finished = true;
    Wait wait;     // when not finished
    Status error;  // when finished by an error (the run fails with it)

    static TaskStep done(Status error = {}) { return {true, {}, std::move(error)}; }
    static TaskStep waiting(Wait w) { return {false, std::move(w), {}}; }
};

class Task {
public:
    explicit Task(std::string name) : name_(std::move(name)) {}
    virtual ~Task() = default;
    Task(const Task&) = delete;
    Task& operator=(const Task&) = delete;

    const std::string& name() const { return name_; }
    // Run until the task waits or ends. `last` is how its previous wait ended (ready on the first resume); a task
    // should end soon after `cancelled`.
    virtual TaskStep resume(WaitOutcome last) = 0;
    // The run was cancelled (called before each resume while it is): a task running code of its own makes that code
    // stop (the Lua hook is re-armed).
    virtual void on_cancel() {}
    // Where a waiting task waits, for messages: "script.lua:12" (empty: unknown).
    virtual std::string where() const { return {}; }

private:
    std::string name_;
};

// Why a task runs: the scheduler's run ends when the tasks of its phase end.
enum class TaskRole {
    main,        // the procedure; its end ends the run's main phase
    background,  // spawned by a procedure; ends with the phase
    cleanup,     // runs after the main phase, however it ended
};

}  // namespace rollsense::runtime
