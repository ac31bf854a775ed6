// Shared by the CLI tests: running the program with a prepared environment,
// and a terminal (pseudo-terminal) for what only happens on a TTY.
#pragma once

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "run_command.hpp"
#include "temp_dir.hpp"

namespace rollsense::testing {

inline std::string rollsense_bin() { return std::string(ROLLSENSE_BIN_DIR) + "/rollsense"; }

inline std::string shell_quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// In a forked child: becomes `rollsense ARGS` (exit 127 if it cannot).
[[noreturn]] inline void exec_rollsense(const std::vector<std::string>& args) {
    std::vector<std::string> all{rollsense_bin()};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
}

// Runs `rollsense ARGS` with stdout and stderr on a pseudo-terminal, with the
// extra environment `env` ("NAME=value"; "NAME=" unsets NAME). Returns what the
// terminal showed and the exit status.
inline CommandRun run_on_terminal(const std::vector<std::string>& args, const std::vector<std::string>& env) {
    int master = -1;
    const pid_t pid = ::forkpty(&master, nullptr, nullptr, nullptr);
    REQUIRE(pid >= 0);
    if (pid == 0) {
        for (const auto& e : env) {
            const auto eq = e.find('=');
            if (eq + 1 == e.size())
                ::unsetenv(e.substr(0, eq).c_str());
            else
                ::setenv(e.substr(0, eq).c_str(), e.substr(eq + 1).c_str(), 1);
        }
        exec_rollsense(args);
    }
    CommandRun r;
    char buf[4096];
    for (;;) {
        const ssize_t n = ::read(master, buf, sizeof buf);
        if (n <= 0) break;  // EIO once the child has closed the terminal
        r.output.append(buf, static_cast<std::size_t>(n));
    }
    int st = 0;
    ::waitpid(pid, &st, 0);
    ::close(master);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

}  // namespace rollsense::testing
