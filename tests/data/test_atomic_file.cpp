// Where an atomic write lands (review: `-o /dev/stdout` as root replaced the
// /dev/stdout link with a regular file, and a FIFO's reader got nothing): the
// path itself is replaced, a symbolic link there too (what it named is left as
// it was: a dataset copied with `cp -rs` must not write into the original);
// this process's descriptors, FIFOs and terminals are written in place.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include "rollsense/atomic_file.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
namespace fs = std::filesystem;

TEST_CASE("an atomic write replaces a symbolic link at its path and leaves the file it named") {
    const testing::TempDir dir("rollsense-atomic-link");
    std::ofstream(dir.path() / "target.csv") << "old\n";
    fs::create_symlink("target.csv", dir.path() / "link.csv");
    REQUIRE(write_file_atomic(dir.path() / "link.csv", "new\n").ok());
    CHECK_FALSE(fs::is_symlink(dir.path() / "link.csv"));
    CHECK(testing::read_file(dir.path() / "link.csv") == "new\n");
    CHECK(testing::read_file(dir.path() / "target.csv") == "old\n");
}

TEST_CASE("an atomic write into a FIFO writes in place: the reader gets the content, the FIFO stays") {
    const testing::TempDir dir("rollsense-atomic-fifo");
    const fs::path fifo = dir.path() / "out.csv";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // The read end first, so the write's open does not wait; were the FIFO replaced instead, this end would read
    // end-of-file (no writer), not hang.
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    REQUIRE(reader >= 0);
    REQUIRE(::fcntl(reader, F_SETFL, 0) == 0);
    REQUIRE(write_file_atomic(fifo, "a,b\n1,2\n").ok());
    std::string got;
    char buf[64];
    for (ssize_t n; (n = ::read(reader, buf, sizeof buf)) > 0;) got.append(buf, static_cast<std::size_t>(n));
    ::close(reader);
    CHECK(got == "a,b\n1,2\n");
    CHECK(fs::is_fifo(fifo));
    CHECK(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()) == 1);  // no temporary left
}

TEST_CASE("this process's descriptor is written in place, through the links that lead to it") {
    const testing::TempDir dir("rollsense-atomic-descriptor");
    int pipe_fds[2];
    REQUIRE(::pipe(pipe_fds) == 0);
    const std::string n = std::to_string(pipe_fds[1]);
    fs::create_symlink("/dev/fd/" + n, dir.path() / "abs.csv");
    fs::create_symlink("../../../../../../../../proc/self/fd/" + n, dir.path() / "rel.csv");
    for (const auto& path : {fs::path("/dev/fd/" + n), dir.path() / "abs.csv", dir.path() / "rel.csv"}) {
        INFO(path);
        CHECK(landing_of(path).descriptor == pipe_fds[1]);
        REQUIRE(write_file_atomic(path, "x").ok());
    }
    ::close(pipe_fds[1]);
    char buf[8] = {};
    CHECK(::read(pipe_fds[0], buf, sizeof buf) == 3);
    ::close(pipe_fds[0]);
    CHECK(fs::is_symlink(dir.path() / "abs.csv"));
    // Not ours: a name that is not the descriptor's (leading zero), a path the kernel would not resolve.
    CHECK(landing_of("/dev/fd/0" + n).descriptor == -1);
    CHECK(landing_of("/dev/fd/" + n + "/../" + n).descriptor == -1);
}
