#include "runtime/lua/sandbox.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

#include "rollsense/log.hpp"
#include "runtime/lua/api.hpp"
#include "runtime/lua/pattern_guard.hpp"

namespace rollsense::runtime {
namespace {

constexpr int kHookEvery = 10000;  // instructions between watchdog checks
constexpr std::size_t kMaxModuleName = 200;

// A module name is dotted identifiers: "lib.helper". Nothing else can reach
// a path outside the module roots ('/', '..', a leading '.').
bool plain_module_name(const std::string& name) {
    if (name.empty() || name.size() > kMaxModuleName) return false;
    bool start = true;
    for (char c : name) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '.') {
            if (start) return false;  // empty segment
            start = true;
        } else if (std::isalpha(u) || c == '_' || (!start && std::isdigit(u))) {
            start = false;
        } else {
            return false;
        }
    }
    return !start;
}

// `file` lies inside `root` once symbolic links are resolved.
bool inside(const std::filesystem::path& root, const std::filesystem::path& file) {
    std::error_code ec1, ec2;
    const auto r = std::filesystem::weakly_canonical(root, ec1);
    const auto f = std::filesystem::weakly_canonical(file, ec2);
    if (ec1 || ec2) return false;
    auto [ri, fi] = std::mismatch(r.begin(), r.end(), f.begin(), f.end());
    return ri == r.end();
}

double wall_ms() {
    using namespace std::chrono;
    return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

double thread_cpu_ms() {  // what this thread computed: the scheduler's preemption of a loaded machine is not the script's
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

// Base functions a script may use. Everything else is absent, not stubbed.
constexpr const char* kBaseWhitelist[] = {"assert", "error",    "ipairs",   "next",      "pairs",
                                          "pcall",  "rawequal", "rawget",   "rawlen",    "rawset",
                                          "select", "setmetatable", "getmetatable", "tonumber", "tostring",
                                          "type",   "xpcall",   "_VERSION"};
constexpr const char* kOsWhitelist[] = {"clock", "date", "difftime", "time", "getenv"};

void copy_library(lua_State* L, int env, const char* name, const char* const* keep, std::size_t n_keep,
                  const char* drop = nullptr) {
    if (lua_getglobal(L, name) != LUA_TTABLE) return lua_pop(L, 1);  // a library this Lua lacks
    int lib = lua_gettop(L);
    lua_newtable(L);
    if (keep) {
        for (std::size_t i = 0; i < n_keep; ++i) {
            lua_getfield(L, lib, keep[i]);
            lua_setfield(L, -2, keep[i]);
        }
    } else {
        lua_pushnil(L);
        while (lua_next(L, lib)) {
            if (!(drop && lua_type(L, -2) == LUA_TSTRING && std::strcmp(lua_tostring(L, -2), drop) == 0)) {
                lua_pushvalue(L, -2);
                lua_insert(L, -2);
                lua_settable(L, -4);
            } else {
                lua_pop(L, 1);
            }
        }
    }
    lua_setfield(L, env, name);
    lua_pop(L, 1);
}

}  // namespace

Sandbox::Sandbox(SandboxLimits limits, std::vector<std::filesystem::path> module_path)
    : limits_(limits), module_path_(std::move(module_path)), heap_{limits.memory_bytes, 0, nullptr, {}} {
    L_ = lua_newstate(&LuaHeap::allocate, &heap_);
    if (!L_) throw StatusError(Status(ErrorCode::io_error, "cannot create a Lua state (out of memory)"));
    *static_cast<Sandbox**>(lua_getextraspace(L_)) = this;  // inherited by every coroutine
    luaL_openlibs(L_);
    build_environment();
    arm(L_);
}

Sandbox::~Sandbox() { if (L_) lua_close(L_); }

Sandbox& Sandbox::of(lua_State* L) { return **static_cast<Sandbox**>(lua_getextraspace(L)); }

void* LuaHeap::allocate(void* heap, void* ptr, std::size_t osize, std::size_t nsize) {
    auto* self = static_cast<LuaHeap*>(heap);
    const std::size_t old = ptr ? osize : 0;
    if (nsize == 0) {
        std::free(ptr);
        self->used -= old;
        return nullptr;
    }
    // Past the cap: fail the allocation (freeing, as when the state closes, always works).
    // The stack is safe to ask here while a reallocation keeps the old one valid (Lua < 5.4.6); later, no line.
    if (nsize > old && self->used + (nsize - old) > self->cap) {
        self->refused_at = self->running && LUA_VERSION_RELEASE_NUM < 50406 ? script_line(self->running, 0) : ScriptLine{};
        return nullptr;
    }
    void* p = std::realloc(ptr, nsize);
    if (p) self->used = self->used - old + nsize;
    return p;
}

void Sandbox::build_environment() {
    lua_State* L = L_;
    lua_newtable(L);
    int env = lua_gettop(L);
    lua_pushglobaltable(L);
    int g = lua_gettop(L);
    for (const char* name : kBaseWhitelist) {
        lua_getfield(L, g, name);
        lua_setfield(L, env, name);
    }
    lua_pop(L, 1);
    copy_library(L, env, "string", nullptr, 0, "dump");  // no bytecode out
    lua_getfield(L, env, "string");
    guard_string_patterns(L);
    lua_pop(L, 1);
    for (auto [name, guard] : {std::pair{"setmetatable", &Sandbox::lua_setmetatable}, std::pair{"xpcall", &Sandbox::lua_xpcall}})
        lua_getfield(L, env, name), lua_pushcclosure(L, guard, 1), lua_setfield(L, env, name);  // the original: upvalue 1
    copy_library(L, env, "table", nullptr, 0);
    copy_library(L, env, "math", nullptr, 0);
    lua_getfield(L, env, "math");  // Lua seeds math.random anew in every process: a run would not be reproducible
    for (const char* name : {"random", "randomseed"})
        lua_pushcfunction(L, [](lua_State* S) { return luaL_error(S, "math.random is not reproducible (Lua seeds it "
            "anew in every process): use rs.random() or rs.random_normal(), seeded by --seed and the trial"); }),
            lua_setfield(L, -2, name);
    lua_pop(L, 1);
    copy_library(L, env, "utf8", nullptr, 0);
    copy_library(L, env, "os", kOsWhitelist, std::size(kOsWhitelist));
    lua_pushvalue(L, env);
    lua_setfield(L, env, "_G");
    for (auto [name, fn] : {std::pair{"print", &Sandbox::lua_print}, std::pair{"load", &Sandbox::lua_load_text},
                            std::pair{"require", &Sandbox::lua_require}})
        lua_pushcfunction(L, fn), lua_setfield(L, env, name);
    lua_newtable(L);
    loaded_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
    env_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
    // The string metatable's __index is the real string library, which still has dump; point it at the sandbox copy.
    lua_pushliteral(L, "");
    lua_getmetatable(L, -1);
    lua_rawgeti(L, LUA_REGISTRYINDEX, env_ref_);
    lua_getfield(L, -1, "string");
    lua_setfield(L, -3, "__index");
    lua_pop(L, 3);
}

Status Sandbox::load_file(const std::filesystem::path& file) {
    if (std::error_code ec; !std::filesystem::exists(file, ec))
        return {ErrorCode::not_found, file.string() + ": no such script"};
    return bind_loaded(luaL_loadfilex(L_, file.c_str(), "t"));  // "t": text only; a precompiled chunk is refused
}

Status Sandbox::load_string(const std::string& code, const std::string& chunk_name) {
    return bind_loaded(luaL_loadbufferx(L_, code.data(), code.size(), ("=" + chunk_name).c_str(), "t"));
}

Status Sandbox::bind_loaded(int rc) {
    if (rc != LUA_OK) {
        Status s{ErrorCode::parse_error, lua_tostring(L_, -1)};
        lua_pop(L_, 1);
        return s;
    }
    lua_rawgeti(L_, LUA_REGISTRYINDEX, env_ref_);
    lua_setupvalue(L_, -2, 1);
    return {};
}

int Sandbox::lua_load_text(lua_State* L) {
    auto& self = of(L);
    size_t len = 0;
    const char* code = luaL_checklstring(L, 1, &len);  // strings only: no reader functions
    const char* name = luaL_optstring(L, 2, "=(load)");
    const char* mode = luaL_optstring(L, 3, "t");
    if (std::strcmp(mode, "t") != 0) return luaL_error(L, "load: only text chunks are allowed (mode 't')");
    if (luaL_loadbufferx(L, code, len, name, "t") != LUA_OK) {
        lua_pushnil(L);
        lua_insert(L, -2);
        return 2;
    }
    if (lua_gettop(L) >= 5 && !lua_isnil(L, 4)) lua_pushvalue(L, 4);
    else lua_rawgeti(L, LUA_REGISTRYINDEX, self.env_ref_);
    lua_setupvalue(L, -2, 1);
    return 1;
}

std::string script_log_entry(lua_State* L, char separator) {
    constexpr std::size_t kMax = 64 * 1024;
    std::string entry;
    for (int i = 1; i <= lua_gettop(L) && entry.size() <= kMax; ++i) {
        std::size_t n = 0;
        const char* text = luaL_tolstring(L, i, &n);
        if (i > 1) entry += separator;
        for (std::size_t k = 0; k < n && entry.size() <= kMax; ++k)
            entry += text[k] == '\n' ? "\n  " : text[k] == '\r' ? "\\r" : std::string(1, text[k]);
        lua_pop(L, 1);
    }
    if (entry.size() > kMax) entry.resize(kMax), entry += " ... (cut at 64 KiB)";
    return entry;
}

int Sandbox::lua_print(lua_State* L) {
    log_info("script", script_log_entry(L, '\t'));
    return 0;
}

int Sandbox::lua_require(lua_State* L) {
    auto& self = of(L);
    std::size_t length = 0;
    const char* given = luaL_checklstring(L, 1, &length);
    const std::string name(given, length);  // whole: "lib.helper\0/../x" is no module name (sandbox review)
    if (name == "rollsense") {
        lua_rawgeti(L, LUA_REGISTRYINDEX, self.api_ref_);
        return 1;
    }
    if (!plain_module_name(name))
        return luaL_error(L,
                          "require('%s'): a module name is identifiers joined by '.', e.g. 'lib.helper' for "
                          "lib/helper.lua beside the script or in share/lua (at most %d characters)",
                          name.substr(0, 60).c_str(), static_cast<int>(kMaxModuleName));
    lua_rawgeti(L, LUA_REGISTRYINDEX, self.loaded_ref_);
    if (lua_getfield(L, -1, name.c_str()) != LUA_TNIL) return 1;
    lua_pop(L, 1);
    std::string rel = name;
    for (auto& c : rel)
        if (c == '.') c = '/';
    std::string searched;
    for (const auto& dir : self.module_path_) {
        auto file = dir / (rel + ".lua");
        searched += "\n\t" + file.string();
        if (std::error_code ec; !std::filesystem::exists(file, ec)) continue;
        if (!inside(dir, file))
            return luaL_error(L, "require('%s'): %s leads outside %s (a symbolic link?); modules must lie inside it",
                              name.c_str(), file.c_str(), dir.c_str());
        if (luaL_loadfilex(L, file.c_str(), "t") != LUA_OK)  // a module that does not parse: the script's (exit 3)
            raise_status(L, {ErrorCode::parse_error, "require('" + name + "'): " + lua_tostring(L, -1)});
        lua_rawgeti(L, LUA_REGISTRYINDEX, self.env_ref_);
        lua_setupvalue(L, -2, 1);
        lua_pushstring(L, name.c_str());
        lua_call(L, 1, 1);
        if (lua_isnil(L, -1)) {
            lua_pop(L, 1);
            lua_pushboolean(L, 1);
        }
        lua_pushvalue(L, -1);
        lua_setfield(L, -3, name.c_str());
        return 1;
    }
    return luaL_error(L, "module '%s' not found; searched:%s", name.c_str(), searched.c_str());
}

void Sandbox::hook(lua_State* L, lua_Debug*) {
    auto& self = of(L);
    if (self.external_flag_ && self.external_flag_->load()) self.cancel(self.external_reason_);
    if (self.cancelled_.load()) {
        // Fire on every instruction from now on: a pcall that catches this
        // error runs at most one more instruction before it is raised again.
        lua_sethook(L, &Sandbox::hook, LUA_MASKCOUNT, 1);
        luaL_where(L, 0);  // the line it was running (luaL_error's level 1 is its caller: none in the main chunk)
        lua_pushfstring(L, "%scancelled: %s", lua_tostring(L, -1), self.cancel_reason_.c_str()), lua_error(L);
    }
    const double ran = wall_ms() - self.slice_start_;
    // Hardware review: a finger pushing in current mode ran 130 deg past its limit while the script computed.
    const double computed = self.moving_ ? thread_cpu_ms() - self.slice_cpu_start_ : 0;
    const std::string moving = computed > self.motion_ms_ ? self.moving_() : "";
    if (ran > self.limits_.max_slice_ms || !moving.empty()) {  // the script's failure (cancel_code), not a cancel from outside
        luaL_where(L, 0);  // in a hook, level 0 is the running function: the script's file:line
        const auto ms = [](double v) { return std::to_string(static_cast<long>(v)); };
        const std::string why =
            moving.empty() ? "the script ran " + ms(ran) + " ms without waiting (an endless loop?), past --slice-limit-ms " +
                                 ms(self.limits_.max_slice_ms) + "; let long loops wait (rs.wait), or raise --slice-limit-ms"
                           : "the script computed " + ms(computed) + " ms without waiting while " + moving + ", past " +
                                 ms(self.motion_ms_) + " ms: on a real clock the kernel checks limits between the "
                                 "script's waits; let it wait (rs.wait) sooner";
        self.cancel(lua_tostring(L, -1) + why);
        self.cancel_code_ = ErrorCode::limit_violation;
        lua_sethook(L, &Sandbox::hook, LUA_MASKCOUNT, 1);
        lua_pushstring(L, self.cancel_reason_.c_str()), lua_error(L);
    }
}

void Sandbox::arm(lua_State* thread) {
    lua_sethook(thread, &Sandbox::hook, LUA_MASKCOUNT, cancelled_.load() ? 1 : kHookEvery);
}

void Sandbox::cancel(const std::string& reason) {
    if (!cancelled_.load()) cancel_reason_ = reason;
    cancelled_.store(true);
}

void Sandbox::clear_cancel() {
    cancelled_.store(false);
    cancel_reason_.clear();
    cancel_code_ = ErrorCode::cancelled;
    arm(L_);  // a wait_until condition may have left the main state's hook on every instruction
}

void Sandbox::start_slice(lua_State* running) {
    heap_.running = running;
    slice_start_ = wall_ms();
    if (moving_) slice_cpu_start_ = thread_cpu_ms();
    in_lua_since_ms_.store(static_cast<std::int64_t>(slice_start_) + 1);  // never 0
}

std::string Sandbox::memory_cap() const {
    return "its memory cap (" + std::to_string(limits_.memory_bytes >> 20) + " MB, " +
           std::to_string(heap_.used >> 20) + " MB in use)";
}

std::string Sandbox::memory_error(const std::string& when) const {
    const std::string at = heap_.refused_at[0] ? std::string(heap_.refused_at.data()) + ": " : "";
    return at + "not enough memory: the script reached " + memory_cap() + when + "; raise it with --memory-limit-mb MB";
}

ScriptLine script_line(lua_State* L, int level) noexcept {
    ScriptLine out{};
    for (lua_Debug ar; lua_getstack(L, level, &ar) && !out[0]; ++level)
        if (lua_getinfo(L, "Sl", &ar) && ar.currentline > 0)
            std::snprintf(out.data(), out.size(), "%s:%d", ar.short_src, ar.currentline);
    return out;
}

Status Sandbox::charge(std::size_t bytes, const std::string& what) const {
    if (heap_.used + bytes <= limits_.memory_bytes) return {};
    return {ErrorCode::limit_violation, what + ": a copy of " + std::to_string(bytes) +
                                            " bytes would take the script past " + memory_cap() +
                                            "; write less at a time, or raise --memory-limit-mb"};
}

namespace {
int results_k(lua_State* L, int, lua_KContext) { return lua_gettop(L); }

// Calls the function a wrapper wraps (its upvalue 1) with the wrapper's arguments.
int call_wrapped(lua_State* L) {
    const int n = lua_gettop(L);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, n, 1);
    return 1;
}
}  // namespace

int Sandbox::lua_setmetatable(lua_State* L) {
    if (lua_istable(L, 2)) {
        lua_pushliteral(L, "__gc");
        if (lua_rawget(L, 2) != LUA_TNIL)
            return luaL_error(L, "setmetatable: a '__gc' field (a finalizer) is not allowed in scripts: Lua runs "
                                 "finalizers where no cancel can stop them; use rs.on_cleanup or a <close> variable");
        lua_pop(L, 1);
    }
    // Lua's own refusal, but raised here: from the wrapped function it would carry no file:line.
    if (luaL_getmetafield(L, 1, "__metatable") != LUA_TNIL) return luaL_error(L, "cannot change a protected metatable");
    return call_wrapped(L);
}


// The script's handler runs only while the run is not cancelled: a handler
// called for the hook's cancel error would run with hooks off.
int Sandbox::lua_guarded_handler(lua_State* L) {
    if (of(L).cancelled()) {
        lua_settop(L, 1);
        return 1;
    }
    return call_wrapped(L);
}

int Sandbox::lua_xpcall(lua_State* L) {
    luaL_checktype(L, 2, LUA_TFUNCTION);
    lua_pushvalue(L, 2);
    lua_pushcclosure(L, &Sandbox::lua_guarded_handler, 1);
    lua_replace(L, 2);
    const int n = lua_gettop(L);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_callk(L, n, LUA_MULTRET, 0, &results_k);  // keeps xpcall yieldable (rs.wait inside it)
    return lua_gettop(L);
}

}  // namespace rollsense::runtime
