// Where an atomic write lands (review: `-o /dev/stdout` as root replaced the
// /dev/stdout link with a regular file, `-o link.csv` the link itself, and a
// FIFO's reader got nothing): through a symbolic link to the file it names,
// replaced atomically with the link kept; in place into a FIFO or a terminal.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <fstream>
#include <future>
#include <sstream>

#include "rollsense/atomic_file.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
namespace fs = std::filesystem;

namespace {
std::string read_all(const fs::path& file) {
    std::ifstream in(file);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}
}  // namespace

TEST_CASE("an atomic write through a symbolic link replaces the file it names and keeps the link") {
    const testing::TempDir dir("rollsense-atomic-link");
    std::ofstream(dir.path() / "target.csv") << "old\n";
    fs::create_symlink("target.csv", dir.path() / "link.csv");
    REQUIRE(write_file_atomic(dir.path() / "link.csv", "new\n").ok());
    CHECK(fs::is_symlink(dir.path() / "link.csv"));
    CHECK(read_all(dir.path() / "target.csv") == "new\n");
    SECTION("a dangling link: the file it names is created") {
        fs::create_symlink("later.csv", dir.path() / "dangling.csv");
        REQUIRE(write_file_atomic(dir.path() / "dangling.csv", "made\n").ok());
        CHECK(fs::is_symlink(dir.path() / "dangling.csv"));
        CHECK(read_all(dir.path() / "later.csv") == "made\n");
    }
}

TEST_CASE("an atomic write into a FIFO writes in place: the reader gets the content, the FIFO stays") {
    const testing::TempDir dir("rollsense-atomic-fifo");
    const fs::path fifo = dir.path() / "out.csv";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    auto reader = std::async(std::launch::async, [&] { return read_all(fifo); });
    REQUIRE(write_file_atomic(fifo, "a,b\n1,2\n").ok());
    CHECK(reader.get() == "a,b\n1,2\n");
    CHECK(fs::is_fifo(fifo));
    CHECK(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()) == 1);  // no temporary left
}
