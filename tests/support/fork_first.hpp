// A child process forked while the test still has one thread, handed a word
// (a device path) once the parent has started the threads that serve it.
//
// Why: fork() copies every lock as it stands at that instant, and a lock held
// by another thread stays held in the child for good. A test that forks while
// an emulator's serving thread runs gives its child a deadlock whenever that
// thread was inside the allocator (AddressSanitizer's allocator has no fork
// handlers: in CI the child hung at its first malloc until its alarm). A child
// that runs in-process code next to a served device is therefore forked first.
#pragma once

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>
#include <string>

namespace rollsense::testing {

class ForkedFirst {
public:
    // Forks now. The child waits for hand_over(), then ends with _exit(body(word));
    // with no word (the parent gave up before handing over) it ends with 3.
    explicit ForkedFirst(const std::function<int(const std::string&)>& body) {
        int fds[2];
        REQUIRE(::pipe(fds) == 0);
        pid_ = ::fork();
        REQUIRE(pid_ >= 0);
        if (pid_ == 0) {
            ::close(fds[1]);
            std::string word;
            char buf[256];
            for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) word.append(buf, static_cast<std::size_t>(n));
            ::_exit(word.empty() ? 3 : body(word));
        }
        ::close(fds[0]);
        to_child_ = fds[1];
    }
    ForkedFirst(const ForkedFirst&) = delete;
    ForkedFirst& operator=(const ForkedFirst&) = delete;
    ~ForkedFirst() {
        close_pipe();
        if (pid_ > 0 && ::kill(pid_, SIGKILL) == 0) ::waitpid(pid_, nullptr, 0);
    }

    void hand_over(const std::string& word) {
        for (std::size_t at = 0; at < word.size();) {
            const ssize_t n = ::write(to_child_, word.data() + at, word.size() - at);
            REQUIRE(n > 0);
            at += static_cast<std::size_t>(n);
        }
        close_pipe();
    }

    // The child's wait status, once it has ended.
    int wait() {
        int status = 0;
        REQUIRE(::waitpid(pid_, &status, 0) == pid_);
        pid_ = -1;
        return status;
    }

private:
    void close_pipe() {
        if (to_child_ >= 0) ::close(to_child_);
        to_child_ = -1;
    }

    pid_t pid_ = -1;
    int to_child_ = -1;
};

}  // namespace rollsense::testing
