// Lua's pattern matcher backtracks in C, where no instruction hook runs: a pattern such as '.-.-.-.-b' on a few dozen
// bytes can run for hours and no cancel can stop it. The sandbox therefore bounds the cost of every pattern before it
// runs (string.find, match, gmatch, gsub), by a documented rule (docs/scripting.md, "Pattern matching"):
//
//   cost = (n + 1)^(r + s) * 2^o  must not exceed 10^9 steps,
//
// n the subject's length in bytes, r the repetition items ('*', '+', '-' and '%b'), o the optional items ('?'), s = 1
// when the match may start at every position (no '^' anchor; gmatch always) and 0 otherwise. That is an upper bound on
// the matcher's backtracking, so whatever passes finishes in a bounded time; ordinary patterns on ordinary strings pass
// (one repetition on 30 kB, three anchored repetitions on 1 kB). A plain find (4th argument true) is no pattern and is
// not checked.
#pragma once

#include <lua.hpp>

#include <cstddef>
#include <string_view>

namespace rollsense::runtime {

// The rule's verdict: 0 if the pattern may run on a subject of `n` bytes, else the base-10 logarithm of its cost bound
// (for the message).
double pattern_cost_log10(std::string_view pattern, std::size_t n, bool every_start);
constexpr double kPatternBudgetLog10 = 9.0;

// Replace find, match, gmatch and gsub in the string library table at the top of L's stack by guarded versions.
void guard_string_patterns(lua_State* L);

}  // namespace rollsense::runtime
