// The Lua state a roll script runs in (ArduPilot-style sandbox):
// - a memory-capped allocator (an allocation past the cap fails, which Lua
//   reports as "not enough memory" at the script's line);
// - a fresh environment with a whitelist: no io, no os.execute/remove/exit,
//   no debug, no dofile/loadfile, no string.dump, no bytecode (load is text-only);
// - `require` that finds only the rollsense module and text modules in the
//   script's folder and share/lua, loaded into the same sandbox;
// - an instruction-count hook for cancellation: once cancelled, the hook
//   re-arms itself to fire on every instruction, so `pcall` cannot swallow it.
#pragma once

#include <lua.hpp>

#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rollsense/status.hpp"
#include "runtime/session/cancellation.hpp"

namespace rollsense::runtime {

struct SandboxLimits {
    std::size_t memory_bytes = 256u << 20;  // Lua heap cap
    double max_slice_ms = 5000;             // Lua may run this long without yielding
};

// The sandbox is the run's Cancellation while a script runs: its instruction
// hook must see the flag at once, and sets it itself (slice limit, Ctrl-C).
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
    // Install the hook on a coroutine (new threads inherit it, this re-arms).
    void arm(lua_State* thread);
    // Called by the scheduler right before resuming Lua code.
    void start_slice();

    std::size_t memory_used() const { return memory_used_; }
    const SandboxLimits& limits() const { return limits_; }

    static Sandbox& of(lua_State* L);  // the sandbox owning a Lua thread

    // A flag set asynchronously (a signal handler, an e-stop thread); the hook
    // turns it into a cancellation with `reason` at the next check.
    void watch_flag(const std::atomic<bool>* flag, std::string reason) {
        external_flag_ = flag;
        external_reason_ = std::move(reason);
    }

private:
    static void* allocate(void* ud, void* ptr, std::size_t osize, std::size_t nsize);
    static void hook(lua_State* L, lua_Debug* ar);
    static int lua_require(lua_State* L);
    static int lua_load_text(lua_State* L);
    static int lua_print(lua_State* L);
    void build_environment();

    SandboxLimits limits_;
    std::vector<std::filesystem::path> module_path_;
    lua_State* L_ = nullptr;
    std::size_t memory_used_ = 0;
    int env_ref_ = LUA_NOREF;
    int api_ref_ = LUA_NOREF;
    int loaded_ref_ = LUA_NOREF;
    std::atomic<bool> cancelled_{false};
    std::string cancel_reason_;
    double slice_start_ = 0;
    const std::atomic<bool>* external_flag_ = nullptr;
    std::string external_reason_;
};

}  // namespace rollsense::runtime
