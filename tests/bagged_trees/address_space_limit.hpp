// Runs a piece of code in a forked child whose address space is capped
// (RLIMIT_AS), so a regression that allocates gigabytes fails the test instead
// of exhausting the machine that runs it.
#pragma once

#include "address_space.hpp"
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <functional>

namespace rollsense::testing {

// What happened to the child: returned true (passed), returned false, or let
// an exception escape (the failure the bounded parsers exist to prevent).
enum class ChildOutcome { passed, failed, threw, crashed };

using rollsense::testing::kCanLimitAddressSpace;  // address_space.hpp: false under ASan

inline ChildOutcome run_with_address_space_limit(std::size_t bytes, const std::function<bool()>& body) {
    const pid_t pid = ::fork();
    if (pid < 0) std::abort();
    if (pid == 0) {
        if (kCanLimitAddressSpace) {
            rlimit limit{bytes, bytes};
            if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(4);
        }
        int code = 3;
        try {
            code = body() ? 0 : 1;
        } catch (...) {
            code = 2;
        }
        ::_exit(code);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
    }
    if (!WIFEXITED(status)) return ChildOutcome::crashed;
    switch (WEXITSTATUS(status)) {
        case 0: return ChildOutcome::passed;
        case 1: return ChildOutcome::failed;
        case 2: return ChildOutcome::threw;
        default: return ChildOutcome::crashed;
    }
}

}  // namespace rollsense::testing
