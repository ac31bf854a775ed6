#include "runtime/lua/lua_task.hpp"

#include <utility>

#include "runtime/lua/api.hpp"
#include "runtime/lua/sandbox.hpp"
#include "runtime/session/session.hpp"

namespace rollsense::runtime {

LuaTask::LuaTask(Sandbox& sandbox, lua_State* L, int function_index, std::string name)
    : Task(std::move(name)), sandbox_(sandbox) {
    lua_State* main = sandbox_.state();
    function_index = lua_absindex(L, function_index);
    thread_ = lua_newthread(main);
    ref_ = luaL_ref(main, LUA_REGISTRYINDEX);
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

void LuaTask::request(Wait wait) {
    waiting_for_ = wait.what;
    pending_ = std::move(wait);
}

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
    sandbox_.start_slice();
    int nres = 0;
    const int status = lua_resume(thread_, main, 0, &nres);
    if (status == LUA_YIELD) {
        lua_pop(thread_, nres);
        return TaskStep::waiting(std::exchange(pending_, Wait{}));
    }
    if (status == LUA_OK) return TaskStep::done();
    const char* msg = lua_tostring(thread_, -1);
    std::string text = msg ? msg : "(error object is not a string)";
    luaL_traceback(main, thread_, text.c_str(), 0);
    std::string trace = lua_tostring(main, -1);
    lua_pop(main, 1);
    // The code a binding raised (a limit violation, a hardware fault) stays the
    // script's error code.
    ErrorCode code = session_of(main)->take_raised_code();
    if (sandbox_.cancelled()) code = ErrorCode::cancelled;
    if (code == ErrorCode::ok) code = ErrorCode::script_error;
    return TaskStep::done(Status(code, trace));
}

std::function<Result<bool>()> lua_predicate(Sandbox& sandbox, int ref) {
    return [&sandbox, ref]() -> Result<bool> {
        lua_State* main = sandbox.state();
        lua_rawgeti(main, LUA_REGISTRYINDEX, ref);
        sandbox.start_slice();
        if (lua_pcall(main, 0, 1, 0) != LUA_OK) {
            std::string msg = lua_tostring(main, -1);
            lua_pop(main, 1);
            return Status(sandbox.cancelled() ? ErrorCode::cancelled : ErrorCode::script_error,
                          "wait_until condition failed: " + msg);
        }
        const bool met = lua_toboolean(main, -1);
        lua_pop(main, 1);
        return met;
    };
}

}  // namespace rollsense::runtime
