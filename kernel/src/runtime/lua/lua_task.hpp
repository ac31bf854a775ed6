// A roll-script procedure as a scheduler task: a Lua coroutine in the sandbox. A binding that waits (rs.wait, j:move,
// rs.wait_until, ...) states its wait with request() and yields; resume() hands that wait to the scheduler, and the
// binding's continuation reads outcome() when the scheduler resumes the coroutine.
#pragma once

#include <lua.hpp>

#include <string>

#include "runtime/session/task.hpp"

namespace rollsense::runtime {

class Sandbox;

class LuaTask final : public Task {
public:
    // The coroutine runs the function at `function_index` of L's stack.
    LuaTask(Sandbox& sandbox, lua_State* L, int function_index, std::string name);
    ~LuaTask() override;  // closes the coroutine (its to-be-closed variables run)

    TaskStep resume(WaitOutcome last) override;
    void on_cancel() override;
    std::string where() const override;

    lua_State* thread() const { return thread_; }
    // Called by a binding right before it yields.
    void request(Wait wait);
    // How the last wait ended, and what it was for (error messages).
    WaitOutcome outcome() const { return outcome_; }
    const std::string& waiting_for() const { return waiting_for_; }
    // A wait_until condition (a registry reference) the task owns until its continuation releases it.
    void hold_predicate(int ref);
    void release_predicate();

private:
    Sandbox& sandbox_;
    lua_State* thread_ = nullptr;
    int ref_ = LUA_NOREF;  // keeps the coroutine alive
    int predicate_ref_ = LUA_NOREF;
    bool first_resume_ = true;  // passes the body to task_body (lua_task.cpp)
    Wait pending_;
    WaitOutcome outcome_ = WaitOutcome::ready;
    std::string waiting_for_;
};

// A wait_until condition as a C++ predicate: calls the Lua function `ref` on the sandbox's main state; a Lua error is
// the predicate's error, naming `called_at` ("file:line", where the script called rs.wait_until).
std::function<Result<bool>()> lua_predicate(Sandbox& sandbox, int ref, std::string called_at);

}  // namespace rollsense::runtime
