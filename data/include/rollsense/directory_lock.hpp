// An advisory lock on a folder, held for as long as the object lives: two
// rollsense runs writing into one output folder would interleave their
// manifests, so the second is refused at once. flock(2) on the folder itself
// (no lock file to leave behind in the dataset); the kernel drops it when the
// process ends, however it ends, so a crash never leaves a stale lock.
#pragma once

#include <filesystem>
#include <string>

#include "rollsense/status.hpp"

namespace rollsense {

class DirectoryLock {
public:
    // Locks `dir` (which must exist) or fails with state_error naming it and
    // `what_for` (e.g. "a rollsense run") when another process holds it.
    static Result<DirectoryLock> acquire(const std::filesystem::path& dir);

    DirectoryLock() = default;
    DirectoryLock(DirectoryLock&& other) noexcept;
    DirectoryLock& operator=(DirectoryLock&& other) noexcept;
    DirectoryLock(const DirectoryLock&) = delete;
    DirectoryLock& operator=(const DirectoryLock&) = delete;
    ~DirectoryLock();

private:
    explicit DirectoryLock(int fd) : fd_(fd) {}
    int fd_ = -1;
};

}  // namespace rollsense
