// Run a piece of a test in a forked child under an address-space limit
// (RLIMIT_AS), so that a regression which allocates without bound fails the
// test instead of exhausting the machine. The child reports a line of text
// through a pipe; a child killed by a signal reports that instead.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <functional>
#include <string>

#include "address_space.hpp"
#include "kernel_fixture.hpp"

namespace sandbox_test {

struct ChildResult {
    bool exited = false;  // false: killed by a signal (SIGSEGV, SIGABRT, ...)
    int code = 0;         // exit code, or the signal number
    std::string text;     // what the child reported
};

// `timeout_s` (0: none) ends a child that hangs with SIGALRM: a dodged cancel
// fails the test instead of hanging it.
inline ChildResult run_limited(std::size_t address_space_bytes, unsigned timeout_s,
                               const std::function<std::string()>& body) {
    int fds[2];
    if (::pipe(fds) != 0) return {false, -1, "pipe failed"};
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fds[0]);
        if (rollsense::testing::kCanLimitAddressSpace) {  // not under ASan (address_space.hpp)
            rlimit lim{address_space_bytes, address_space_bytes};
            ::setrlimit(RLIMIT_AS, &lim);
        }
        if (timeout_s) ::alarm(timeout_s);
        std::string text = body();
        (void)!::write(fds[1], text.data(), text.size());
        ::close(fds[1]);
        ::_exit(0);
    }
    ::close(fds[1]);
    ChildResult r;
    char buf[4096];
    ssize_t n;
    while ((n = ::read(fds[0], buf, sizeof buf)) > 0) r.text.append(buf, static_cast<std::size_t>(n));
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    r.exited = WIFEXITED(status);
    r.code = r.exited ? WEXITSTATUS(status) : WTERMSIG(status);
    return r;
}

constexpr std::size_t kTwoGiB = std::size_t{2} << 30;

// A script run in a limited child: the status message, or how the child died.
inline ChildResult run_script_limited(kt::TempDir& dir, const std::string& script, unsigned timeout_s = 120,
                                      const std::function<void(rollsense::runtime::SessionOptions&)>& adjust = {}) {
    auto o = kt::options_for(dir, script);
    if (adjust) adjust(o);
    return run_limited(kTwoGiB, timeout_s, [&] {
        rollsense::runtime::Session session(o);
        auto s = session.run().status;
        return s.ok() ? std::string("ok") : std::string(rollsense::to_string(s.code())) + ": " + s.message();
    });
}

}  // namespace sandbox_test
