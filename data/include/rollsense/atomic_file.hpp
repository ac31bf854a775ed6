// Durable file writes: write to a temporary file in the same folder, fsync it,
// rename it over the target, fsync the folder. A reader (or a resumed run)
// sees either the old file or the complete new one, never a torn one, even
// after kill -9 or a power cut.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense {

// As above, `file` itself is replaced: a symbolic link there becomes the new file, the file it named is left as it was (in a
// dataset copied with `cp -rs` the copy's files become its own). Written in place instead, as the shell's `>` would,
// for they have no folder entry to replace: this process's open descriptor (/dev/stdout, /dev/fd/N: `>>` appends),
// a FIFO, a terminal, /dev/null (review: `-o /dev/stdout` as root replaced the /dev/stdout link with a file). A
// block device (a disk) is refused.
Status write_file_atomic(const std::filesystem::path& file, std::string_view content);

struct Landing {
    std::filesystem::path file;  // the path as given
    int descriptor = -1;         // this process's descriptor N it leads to (/dev/stdout: 1)
    bool in_place = false;       // it is, through its links, a FIFO, a character device or a socket
    bool block_device = false;   // a disk: refused
    bool written_in_place() const { return descriptor >= 0 || in_place; }
};
// How write_file_atomic and write_files_atomic write `file`.
Landing landing_of(const std::filesystem::path& file);

// What can be told before writing `file` as above: it is not a folder, and its
// folder exists and may be written. For commands that write their result at the
// end of a long job, so that a wrong path fails at once, not after the job. The
// error names `file` and its folder.
Status check_can_write(const std::filesystem::path& file);

// The same for a folder a command creates or fills (run --out, merge OUT):
// neither it nor the nearest part of its path that exists is a file. The error
// (invalid_argument) is "DIR: is a file, not a folder", or "DIR: PART is a file,
// not a folder" for a part of its path; the caller adds the way out.
Status check_can_be_folder(const std::filesystem::path& dir);

// The same for several files at once (group commit): every temporary is written
// and synced before any rename, and the folder is synced once. Each file is
// still atomic on its own. Used by the recorder so that a fast simulated run
// does not pay one folder sync per trial.
struct PendingFile {
    std::filesystem::path file;
    std::string content;
};
Status write_files_atomic(std::vector<PendingFile>& files);

// Several files written in place (no temporary, no rename) and flushed to
// stable storage (one syncfs() for several): for files that another file commits (the
// trial files a manifest lists once they are durable), so that a torn one is
// never read. Half the file-system operations of write_files_atomic.
Status write_files_synced(const std::vector<PendingFile>& files);

// Append to an existing file and flush it to stable storage. A failed write
// cuts the file back to its size before, so it never keeps part of `content`;
// only a crash during the append can (readers of appended files must handle a
// last line without its line end).
Status append_file_durable(const std::filesystem::path& file, std::string_view content);

// Renames `from` to `to` (a file, or a folder onto a missing or empty folder)
// and syncs the folder of `to`, so that the new name survives a power cut. The
// error names `to`.
Status rename_durable(const std::filesystem::path& from, const std::filesystem::path& to);

// Remove temporaries left by an interrupted write (".<name>.tmp-*") in a folder.
void remove_stale_temporaries(const std::filesystem::path& folder);

}  // namespace rollsense
