// An advisory lock on a folder, held for as long as the object lives: two
// rollsense runs writing into one output folder would interleave their
// manifests, so the second is refused at once; a merge reading a shard's
// folder must not see a run change it, nor a run change it under the merge.
// Writers hold it exclusively, readers shared: any number of merges read one
// shard at once. flock(2) on the folder itself (no lock file to leave behind
// in the dataset); the kernel drops it when the process ends, however it
// ends, so a crash never leaves a stale lock.
#pragma once

#include <filesystem>
#include <string>

#include "rollsense/status.hpp"

namespace rollsense {

class DirectoryLock {
public:
    // Locks `dir` (which must exist) to write into it, or fails with
    // state_error naming it and who holds it (a run writing it, or a merge
    // reading it).
    static Result<DirectoryLock> acquire(const std::filesystem::path& dir);
    // Locks `dir` to read it, beside other readers, or fails with state_error
    // when a run is writing it.
    static Result<DirectoryLock> acquire_to_read(const std::filesystem::path& dir);

    DirectoryLock() = default;
    DirectoryLock(DirectoryLock&& other) noexcept;
    DirectoryLock& operator=(DirectoryLock&& other) noexcept;
    DirectoryLock(const DirectoryLock&) = delete;
    DirectoryLock& operator=(const DirectoryLock&) = delete;
    ~DirectoryLock();

private:
    static Result<DirectoryLock> acquire(const std::filesystem::path& dir, bool exclusive);
    explicit DirectoryLock(int fd) : fd_(fd) {}
    int fd_ = -1;
};

}  // namespace rollsense
