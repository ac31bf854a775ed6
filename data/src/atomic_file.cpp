#include "rollsense/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace rollsense {
namespace {

std::string errno_text() { return std::strerror(errno); }

std::filesystem::path temporary_for(const std::filesystem::path& file) {
    static std::atomic<unsigned> counter{0};
    return file.parent_path() /
           ("." + file.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
}

// Every byte of `content` to an open file (retrying short writes).
Status write_all(int fd, const std::filesystem::path& path, std::string_view content) {
    const char* p = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            return {ErrorCode::io_error, path.string() + ": write failed: " + errno_text()};
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    return {};
}

// Write a file; with `sync` also flush it to stable storage before closing.
// Errors name `target`, the file the caller asked for (not its temporary).
Status write_and_sync(const std::filesystem::path& path, std::string_view content, bool sync,
                      const std::filesystem::path& target) {
    int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return {ErrorCode::io_error, target.string() + ": cannot create: " + errno_text()};
    if (auto s = write_all(fd, target, content); !s.ok()) {
        ::close(fd);
        return s;
    }
    if (sync && ::fdatasync(fd) != 0) {
        Status s{ErrorCode::io_error, target.string() + ": fsync failed: " + errno_text()};
        ::close(fd);
        return s;
    }
    if (::close(fd) != 0) return {ErrorCode::io_error, target.string() + ": close failed: " + errno_text()};
    return {};
}

Status sync_folder(const std::filesystem::path& folder) {
    int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return {ErrorCode::io_error, folder.string() + ": cannot open folder to sync: " + errno_text()};
    int rc = ::fsync(fd);
    ::close(fd);
    if (rc != 0) return {ErrorCode::io_error, folder.string() + ": folder fsync failed: " + errno_text()};
    return {};
}

// One syncfs() of the filesystem holding `file`: its data and every folder entry.
Status sync_filesystem_of(const std::filesystem::path& file) {
    int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    const int rc = fd < 0 ? -1 : ::syncfs(fd);
    if (fd >= 0) ::close(fd);
    if (rc != 0) return {ErrorCode::io_error, file.parent_path().string() + ": syncfs failed: " + errno_text()};
    return {};
}

// N when `path` is this process's descriptor N: a name of digits in the folder /proc/<pid>/fd (or a thread's), as
// /dev/fd/N, /proc/self/fd/N and /proc/thread-self/fd/N are once the folder's links are resolved (review: matching
// the text took /dev/fd/2/../1 and /dev/fd/01, and missed a relative link to /dev/fd/1).
int own_descriptor(const std::filesystem::path& path) {
    const std::string name = path.filename().string();
    if (name.empty() || name.size() > 9 || (name.size() > 1 && name[0] == '0') ||
        !std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return -1;
    std::error_code ec;
    const std::string folder = std::filesystem::canonical(path.parent_path(), ec).string();
    const std::string proc = "/proc/" + std::to_string(::getpid());
    const bool ours = folder == proc + "/fd" || (folder.starts_with(proc + "/task/") && folder.ends_with("/fd"));
    return !ec && ours ? std::stoi(name) : -1;
}

}  // namespace

Landing landing_of(const std::filesystem::path& file) {
    namespace fs = std::filesystem;
    std::error_code ec;
    Landing out{file};
    fs::path p = file;
    for (int hop = 0; hop < 40; ++hop) {  // the links only tell whether they lead to one of our descriptors
        if ((out.descriptor = own_descriptor(p)) >= 0) return out;
        if (!fs::is_symlink(p, ec)) break;
        const fs::path to = fs::read_symlink(p, ec);
        if (ec) break;
        p = to.is_absolute() ? to : p.parent_path() / to;
    }
    const auto type = fs::status(file, ec).type();  // the kernel follows the links
    out.in_place = type == fs::file_type::fifo || type == fs::file_type::character || type == fs::file_type::socket;
    out.block_device = type == fs::file_type::block;
    return out;
}

Status write_files_synced(const std::vector<PendingFile>& files) {
    // As write_files_atomic: one file is fdatasync'ed (and its folder synced),
    // several are flushed by one syncfs().
    const bool group = files.size() > 1;
    for (const auto& f : files)
        if (auto s = write_and_sync(f.file, f.content, !group, f.file); !s.ok()) return s;
    if (files.empty()) return {};
    return group ? sync_filesystem_of(files.front().file) : sync_folder(files.front().file.parent_path());
}

Status write_files_atomic(std::vector<PendingFile>& files) {
    for (auto it = files.begin(); it != files.end();) {
        const Landing to = landing_of(it->file);
        if (to.block_device) return {ErrorCode::io_error, it->file.string() + ": is a block device (a disk); name a file"};
        if (!to.written_in_place()) {
            ++it;
            continue;
        }
        // No folder entry to replace, nor data to sync: written as the shell's `>` would (an open descriptor as the
        // shell set it up: `>>` appends).
        if (to.descriptor == STDOUT_FILENO) std::fflush(stdout);
        if (auto s = to.descriptor >= 0 ? write_all(to.descriptor, it->file, it->content)
                                        : write_and_sync(to.file, it->content, false, it->file);
            !s.ok())
            return s;
        it = files.erase(it);
    }
    std::vector<std::filesystem::path> temps;
    temps.reserve(files.size());
    auto discard = [&] {
        std::error_code ec;
        for (const auto& t : temps) std::filesystem::remove(t, ec);
    };
    // One file: fdatasync it. Several: write them all, then one syncfs() of
    // the filesystem flushes every temporary at once (far cheaper than one
    // sync each on slow disks), and only then rename.
    const bool group = files.size() > 1;
    for (const auto& f : files) {
        temps.push_back(temporary_for(f.file));
        if (auto s = write_and_sync(temps.back(), f.content, !group, f.file); !s.ok()) {
            discard();
            return s;
        }
    }
    if (group)
        if (auto s = sync_filesystem_of(temps.front()); !s.ok()) {
            discard();
            return s;
        }
    std::vector<std::filesystem::path> folders;
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (::rename(temps[i].c_str(), files[i].file.c_str()) != 0) {
            Status s{ErrorCode::io_error, files[i].file.string() + ": rename failed: " + errno_text()};
            discard();
            return s;
        }
        auto folder = files[i].file.parent_path();
        bool seen = false;
        for (const auto& f : folders) seen = seen || f == folder;
        if (!seen) folders.push_back(folder);
    }
    for (const auto& folder : folders)
        if (auto s = sync_folder(folder); !s.ok()) return s;
    return {};
}

Status append_file_durable(const std::filesystem::path& file, std::string_view content) {
    int fd = ::open(file.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd < 0) return {ErrorCode::io_error, file.string() + ": cannot open to append: " + errno_text()};
    const off_t before = ::lseek(fd, 0, SEEK_END);
    Status s = before < 0 ? Status{ErrorCode::io_error, file.string() + ": cannot seek: " + errno_text()}
                          : write_all(fd, file, content);
    if (s.ok() && ::fdatasync(fd) != 0) s = {ErrorCode::io_error, file.string() + ": fsync failed: " + errno_text()};
    if (!s.ok() && before >= 0) (void)::ftruncate(fd, before);  // keep no part of a failed append
    if (::close(fd) != 0 && s.ok()) s = {ErrorCode::io_error, file.string() + ": close failed: " + errno_text()};
    return s;
}

Status write_file_atomic(const std::filesystem::path& file, std::string_view content) {
    std::vector<PendingFile> one{{file, std::string(content)}};
    return write_files_atomic(one);
}

Status rename_durable(const std::filesystem::path& from, const std::filesystem::path& to) {
    if (::rename(from.c_str(), to.c_str()) != 0)
        return {ErrorCode::io_error, to.string() + ": cannot take its place: " + errno_text()};
    return sync_folder(to.parent_path());
}

Status check_can_write(const std::filesystem::path& file) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const std::string cannot = "cannot write '" + file.string() + "': ";
    if (fs::is_directory(file, ec)) return {ErrorCode::io_error, cannot + "it is a folder; name a file"};
    const Landing to = landing_of(file);  // in place (a descriptor, a FIFO, a device), or replaced in its folder
    if (to.descriptor >= 0) {
        const int flags = ::fcntl(to.descriptor, F_GETFL);
        if (flags < 0 || (flags & O_ACCMODE) == O_RDONLY)
            return {ErrorCode::io_error, cannot + "descriptor " + std::to_string(to.descriptor) + " is not open for writing"};
        return {};
    }
    if (to.block_device) return {ErrorCode::io_error, cannot + "it is a block device (a disk); name a file"};
    if (to.in_place)
        return ::access(to.file.c_str(), W_OK) == 0 ? Status{} : Status{ErrorCode::io_error, cannot + errno_text()};
    const fs::path folder = to.file.parent_path().empty() ? fs::path(".") : to.file.parent_path();
    if (!fs::is_directory(folder, ec))
        return {ErrorCode::io_error, cannot + "the folder " + folder.string() +
                                         (fs::exists(folder, ec) ? " is not a folder" : " does not exist; create it first")};
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        return {ErrorCode::io_error, cannot + "the folder " + folder.string() + " is not writable: " + errno_text()};
    return {};
}

Status check_can_be_folder(const std::filesystem::path& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (fs::path part = dir; !part.empty(); part = part.parent_path()) {
        if (fs::exists(part, ec)) {  // the nearest part that exists decides
            if (fs::is_directory(part, ec)) return {};
            return {ErrorCode::invalid_argument,
                    dir.string() + ": " + (part == dir ? "is" : part.string() + " is") + " a file, not a folder"};
        }
        if (part == part.parent_path()) break;  // the root
    }
    return {};
}

void remove_stale_temporaries(const std::filesystem::path& folder) {
    std::error_code ec;
    for (auto it = std::filesystem::directory_iterator(folder, ec); !ec && it != std::filesystem::directory_iterator();
         it.increment(ec)) {
        const auto name = it->path().filename().string();
        if (name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos)
            std::filesystem::remove(it->path(), ec);
    }
}

}  // namespace rollsense
