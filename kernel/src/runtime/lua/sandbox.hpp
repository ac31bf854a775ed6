// The Lua state a roll script runs in (ArduPilot-style sandbox):
// - a memory-capped allocator (an allocation past the cap fails, which Lua reports as "not enough memory"; the
//   allocator notes the script's line);
// - a fresh environment with a whitelist: no io, no os.execute/remove/exit, no debug, no dofile/loadfile, no
//   string.dump, no bytecode (load is text-only);
// - `require` that finds only the rollsense module and text modules in the script's folder and share/lua, loaded
//   into the same sandbox;
// - an instruction-count hook for cancellation: once cancelled, the hook re-arms itself to fire on every
//   instruction, so `pcall` cannot swallow it; xpcall skips the script's message handler once cancelled (a handler
//   runs where hooks are off when the error came from the hook), and every task body runs under a pcall of the
//   kernel's so that its `<close>` variables are closed with hooks on (see lua_task.cpp);
// - no finalizers: setmetatable refuses a `__gc` field (Lua runs finalizers with hooks off, so no cancel could stop
//   one);
// - pattern matching bounded in cost (pattern_guard.hpp);
// - copies C++ makes of script data are charged against the heap cap (charge()).
#pragma once

#include <lua.hpp>

#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rollsense/status.hpp"
#include "runtime/session/cancellation.hpp"

namespace rollsense::runtime {

// "script.lua:12", the innermost Lua line at or below stack `level` of L (empty if none); no allocation, no throw.
using ScriptLine = std::array<char, LUA_IDSIZE + 24>;
ScriptLine script_line(lua_State* L, int level) noexcept;

struct SandboxLimits {
    std::size_t memory_bytes = 256u << 20;  // Lua heap cap
    double max_slice_ms = 5000;             // Lua may run this long without yielding
    double cancel_grace_ms = 5000;          // after a cancel, the watchdog's patience (cancel_watchdog.hpp)
};

// The values at L's stack as one log entry (print, rs.log, rs.warn): at most 64 KiB, each line break indented and a
// carriage return shown as \r, so no line of it reads as the program's own (review: an 11 MB line; "\nerror ..." and
// "\rerror ..." faked one).
std::string script_log_entry(lua_State* L, char separator);

// A Lua heap with a cap, for the sandbox and for profiles: an allocation past it fails, and Lua raises "not enough
// memory" in the script.
struct LuaHeap {
    std::size_t cap = 0;
    std::size_t used = 0;
    lua_State* running = nullptr;  // the thread a slice runs: a refusal notes its line, which Lua's error lacks
    ScriptLine refused_at{};       // "script.lua:12", the last refusal's line ("" outside a slice)
    static void* allocate(void* heap, void* ptr, std::size_t osize, std::size_t nsize);
};

// The sandbox is the run's Cancellation while a script runs: its instruction hook must see the flag at once, and
// sets it itself (slice limit, Ctrl-C).
class Sandbox final : public Cancellation {
public:
    Sandbox(SandboxLimits limits, std::vector<std::filesystem::path> module_path);
    ~Sandbox() override;
    Sandbox(const Sandbox&) = delete;
    Sandbox& operator=(const Sandbox&) = delete;

    lua_State* state() const { return L_; }
    // Registry reference of the sandbox environment table.
    int env_ref() const { return env_ref_; }
    // The module returned by require("rollsense"); set by the bindings.
    void set_api_module(int ref) { api_ref_ = ref; }

    // Load a script file as text with the sandbox environment; pushes the chunk.
    Status load_file(const std::filesystem::path& file);
    // Load a string (tests, --eval); pushes the chunk.
    Status load_string(const std::string& code, const std::string& chunk_name);

    // Cancellation: every Lua thread notices at its next instruction.
    void cancel(const std::string& reason) override;
    void clear_cancel() override;
    bool cancelled() const override { return cancelled_.load(); }
    const std::string& cancel_reason() const override { return cancel_reason_; }
    // What a task ended by the cancel failed of: limit_violation past the slice limit, else cancelled.
    ErrorCode cancel_code() const { return cancel_code_; }
    // Install the hook on a coroutine (new threads inherit it, this re-arms).
    void arm(lua_State* thread);
    // Called by the scheduler right before resuming Lua code, and right after Lua hands control back (the cancel
    // watchdog watches the gap).
    void start_slice(lua_State* running);
    void end_slice() { in_lua_since_ms_.store(0); heap_.running = nullptr; }
    // Monotonic ms since Lua was entered, 0 when Lua is not running.
    std::int64_t in_lua_since_ms() const { return in_lua_since_ms_.load(); }

    // A copy of `bytes` C++ makes for the script (`what`, for the message): refused when the Lua heap plus the copy
    // would pass the cap.
    Status charge(std::size_t bytes, const std::string& what) const;

    std::string memory_cap() const;  // "its memory cap (256 MB, 255 MB in use)"
    // "s.lua:4: not enough memory: the script reached its memory cap (…)<when>; raise it with --memory-limit-mb MB"
    std::string memory_error(const std::string& when = "") const;
    const SandboxLimits& limits() const { return limits_; }

    static Sandbox& of(lua_State* L);  // the sandbox owning a Lua thread

    // A flag set asynchronously (a signal handler, an e-stop thread); the hook turns it into a cancellation with
    // `reason` at the next check.
    void watch_flag(const std::atomic<bool>* flag, std::string reason) {
        external_flag_ = flag;
        external_reason_ = std::move(reason);
    }
    // A slice that computes (CPU time) past `ms` also ends the script while `moving()` names something that moves on by
    // itself between control periods (Session: on a real clock, whose limits and controllers run between slices only).
    void watch_motion(double ms, std::function<std::string()> moving) { motion_ms_ = ms, moving_ = std::move(moving); }

private:
    // The chunk luaL_load* pushed (rc its result) gets the sandbox's environment; a load error is popped, returned.
    Status bind_loaded(int rc);
    static void hook(lua_State* L, lua_Debug* ar);
    static int lua_require(lua_State* L);
    static int lua_load_text(lua_State* L);
    static int lua_print(lua_State* L);
    static int lua_setmetatable(lua_State* L);
    static int lua_xpcall(lua_State* L);
    static int lua_guarded_handler(lua_State* L);
    void build_environment();

    SandboxLimits limits_;
    std::vector<std::filesystem::path> module_path_;
    lua_State* L_ = nullptr;
    LuaHeap heap_;
    int env_ref_ = LUA_NOREF;
    int api_ref_ = LUA_NOREF;
    int loaded_ref_ = LUA_NOREF;
    std::atomic<bool> cancelled_{false};
    std::string cancel_reason_;
    ErrorCode cancel_code_ = ErrorCode::cancelled;  // set and read on the Lua thread
    double slice_start_ = 0;
    double slice_cpu_start_ = 0;  // this thread's CPU ms, with moving_
    std::atomic<std::int64_t> in_lua_since_ms_{0};
    const std::atomic<bool>* external_flag_ = nullptr;
    std::string external_reason_;
    double motion_ms_ = 0;  // with moving_ (watch_motion)
    std::function<std::string()> moving_;
};

}  // namespace rollsense::runtime
