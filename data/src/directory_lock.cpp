#include "rollsense/directory_lock.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <utility>

namespace rollsense {

Result<DirectoryLock> DirectoryLock::acquire(const std::filesystem::path& dir) { return acquire(dir, true); }

Result<DirectoryLock> DirectoryLock::acquire_to_read(const std::filesystem::path& dir) { return acquire(dir, false); }

Result<DirectoryLock> DirectoryLock::acquire(const std::filesystem::path& dir, bool exclusive) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return Error{ErrorCode::io_error, dir.string() + ": cannot open to lock it: " + std::strerror(errno)};
    if (::flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) != 0) {
        const int err = errno;
        // Held by readers only when a shared lock is still to be had (a reader
        // was refused by a writer: no need to ask).
        const bool readers = err == EWOULDBLOCK && exclusive && ::flock(fd, LOCK_SH | LOCK_NB) == 0;
        ::close(fd);
        if (err == EWOULDBLOCK && readers)
            return Error{ErrorCode::state_error, dir.string() + " is being read by a rollsense merge; wait for it to "
                                                                 "end, or choose another folder with --out"};
        if (err == EWOULDBLOCK && exclusive)
            return Error{ErrorCode::state_error, dir.string() +
                                                     " is being written by another rollsense run; wait for it to end, "
                                                     "or choose another folder with --out"};
        if (err == EWOULDBLOCK)
            return Error{ErrorCode::state_error,
                         dir.string() + " is being recorded by a rollsense run; wait for it to end"};
        return Error{ErrorCode::io_error, dir.string() + ": cannot lock: " + std::strerror(err)};
    }
    return DirectoryLock(fd);
}

DirectoryLock::DirectoryLock(DirectoryLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

DirectoryLock& DirectoryLock::operator=(DirectoryLock&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
}

DirectoryLock::~DirectoryLock() {
    if (fd_ >= 0) ::close(fd_);  // closing the last descriptor releases the flock
}

}  // namespace rollsense
