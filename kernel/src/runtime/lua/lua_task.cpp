#include "runtime/lua/lua_task.hpp"

#include <utility>

#include "runtime/lua/api.hpp"
#include "runtime/lua/error_text.hpp"
#include "runtime/lua/sandbox.hpp"
#include "runtime/session/session.hpp"

namespace rollsense::runtime {
namespace {

// "etroll.lua:142, called from demo.lua:18": the innermost Lua line and, when elsewhere, the task function's (review).
std::string stack_lines(lua_State* L) {
    std::string inner, outer;
    lua_Debug ar;
    for (int level = 0; lua_getstack(L, level, &ar); ++level)
        if (lua_getinfo(L, "Sl", &ar) && ar.currentline > 0)
            (inner.empty() ? inner : outer) = std::string(ar.short_src) + ":" + std::to_string(ar.currentline);
    return outer.empty() || outer == inner ? inner : inner + ", called from " + outer;
}

// The error's text and the traceback, taken where the error was raised (the kernel's pcall below unwinds the stack
// before the scheduler looks). Called for the hook's cancel error with hooks off: no __tostring then. An error raised
// inside a module also says the script's line (lab review: a joint limit named only etroll.lua's line).
int task_message_handler(lua_State* L) {
    std::string text = Sandbox::of(L).cancelled() ? error_text_raw(L, 1) : error_text(L, 1);
    if (const auto lines = stack_lines(L); !Sandbox::of(L).cancelled() && lines.find(", called from ") != std::string::npos)
        text += " (" + lines.substr(lines.find(", ") + 2) + ")";
    luaL_traceback(L, L, text.c_str(), 1);
    return 1;
}

int task_body_k(lua_State* L, int status, lua_KContext) {
    // Raised again from here, after Lua has closed the body's <close>
    // variables with hooks back on; the coroutine ends with the handler's text.
    if (status != LUA_OK && status != LUA_YIELD) return lua_error(L);
    return 0;
}

// Every task's body runs under this pcall. An error the hook raises leaves hooks off until a pcall catches it; a
// coroutine that died of it would run its `<close>` variables (when closed) with hooks off, and a looping __close
// could not be stopped. Caught here, they run with hooks on.
int task_body(lua_State* L) {
    lua_pushcfunction(L, &task_message_handler);
    lua_insert(L, 1);
    return task_body_k(L, lua_pcallk(L, 0, 0, 1, 0, &task_body_k), 0);
}

}  // namespace

LuaTask::LuaTask(Sandbox& sandbox, lua_State* L, int function_index, std::string name)
    : Task(std::move(name)), sandbox_(sandbox) {
    // Allocated on the caller's thread: out of memory is an error in the
    // script that spawned, not a panic of the main state outside any pcall.
    function_index = lua_absindex(L, function_index);
    thread_ = lua_newthread(L);
    ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
    lua_pushcfunction(thread_, &task_body);
    lua_pushvalue(L, function_index);
    lua_xmove(L, thread_, 1);
    sandbox_.arm(thread_);
}

LuaTask::~LuaTask() {
    lua_State* main = sandbox_.state();
    release_predicate();
    close_thread(thread_, main);
    luaL_unref(main, LUA_REGISTRYINDEX, ref_);
}

void LuaTask::on_cancel() { sandbox_.arm(thread_); }

std::string LuaTask::where() const { return stack_lines(thread_); }

void LuaTask::request(Wait wait) { waiting_for_ = wait.what, pending_ = std::move(wait); }

void LuaTask::hold_predicate(int ref) {
    release_predicate();
    predicate_ref_ = ref;
}

void LuaTask::release_predicate() {
    if (predicate_ref_ == LUA_NOREF) return;
    luaL_unref(sandbox_.state(), LUA_REGISTRYINDEX, predicate_ref_);
    predicate_ref_ = LUA_NOREF;
}

TaskStep LuaTask::resume(WaitOutcome last) {
    lua_State* main = sandbox_.state();
    outcome_ = last;
    sandbox_.start_slice(thread_);
    int nres = 0;
    const int status = lua_resume(thread_, main, std::exchange(first_resume_, false) ? 1 : 0, &nres);
    sandbox_.end_slice();
    if (status == LUA_YIELD) {
        lua_pop(thread_, nres);
        return TaskStep::waiting(std::exchange(pending_, Wait{}));
    }
    if (status == LUA_OK) return TaskStep::done();
    // The text task_message_handler made; a memory error comes bare (no handler
    // runs for it): the line the allocator noted, which cap, and the way out.
    const std::string trace = status == LUA_ERRMEM ? sandbox_.memory_error() : error_text_raw(thread_, -1);
    // The code a binding raised (a limit violation, a hardware fault) stays the script's error code.
    ErrorCode code = session_of(main)->take_raised_code(trace);
    if (sandbox_.cancelled()) code = sandbox_.cancel_code();
    if (code == ErrorCode::ok) code = ErrorCode::script_error;
    // No traceback for a refused --set (it names its declaration) or a cancel (it names its line; README: Ctrl-C).
    const bool bare = code == ErrorCode::bad_setting || code == ErrorCode::cancelled;
    return TaskStep::done(Status(code, bare ? trace.substr(0, trace.find("\nstack traceback:")) : trace));
}

std::function<Result<bool>()> lua_predicate(Sandbox& sandbox, int ref, std::string called_at) {
    return [&sandbox, ref, called_at = std::move(called_at)]() -> Result<bool> {
        lua_State* main = sandbox.state();
        lua_rawgeti(main, LUA_REGISTRYINDEX, ref);
        sandbox.start_slice(main);
        const int rc = lua_pcall(main, 0, 1, 0);
        sandbox.end_slice();
        if (rc != LUA_OK) {
            // Any error value: nil, a table, a userdata (hooks are on again here).
            const std::string msg = rc == LUA_ERRMEM ? sandbox.memory_error() : error_text(main, -1);
            lua_pop(main, 1);
            const ErrorCode raised = sandbox.cancelled() ? sandbox.cancel_code() : session_of(main)->take_raised_code(msg);
            return Status(raised != ErrorCode::ok ? raised : ErrorCode::script_error,  // a refusal it died of: its code
                          "wait_until condition failed: " + msg + " (the condition of rs.wait_until at " + called_at + ")");
        }
        const bool met = lua_toboolean(main, -1);
        lua_pop(main, 1);
        return met;
    };
}

}  // namespace rollsense::runtime
