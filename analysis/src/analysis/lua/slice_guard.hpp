// Long C++ work a Lua call does (training, cross-validation) is not the
// script's: while it runs the script is out of its slice, so neither the
// no-wait limit nor the cancel watchdog (which ends a run stuck in one call
// past --slice-limit-ms) counts it; a fresh slice starts when it returns.
// A Ctrl-C meanwhile is acted on by the work itself (it polls the cancel).
#pragma once

#include "runtime/lua/sandbox.hpp"

namespace rollsense::runtime::lua_api {

struct SliceGuard {
    SliceGuard(Sandbox& s, lua_State* thread) : sandbox(s), running(thread) { sandbox.end_slice(); }
    ~SliceGuard() { sandbox.start_slice(running); }
    SliceGuard(const SliceGuard&) = delete;
    SliceGuard& operator=(const SliceGuard&) = delete;
    Sandbox& sandbox;
    lua_State* running;  // the thread whose slice resumes
};

}  // namespace rollsense::runtime::lua_api
