// The stock experiment survives kill -9: --resume finishes it, and the dataset
// is byte-identical to an uninterrupted run with the same seed.
#include <catch2/catch.hpp>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace {
namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t lines(const fs::path& p) {
    std::ifstream in(p);
    std::size_t n = 0;
    for (std::string l; std::getline(in, l);) ++n;
    return n;
}

pid_t start(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    REQUIRE(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) == 0);
    return pid;
}

int wait_exit(pid_t pid) {
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::vector<std::string> experiment(const fs::path& out, bool resume) {
    std::vector<std::string> a{std::string(ROLLSENSE_BIN_DIR) + "/rollsense",
                               "run",
                               std::string(ROLLSENSE_SOURCE_DIR) + "/scripts/paper_experiment.lua",
                               "--profile",
                               "sim",
                               "--set",
                               "runs=4",
                               "--set",
                               "analyse=false",
                               "--seed",
                               "11",
                               "--commit-every",
                               "1",
                               "--out",
                               out.string(),
                               "-q"};
    if (resume) a.push_back("--resume");
    return a;
}
}  // namespace

TEST_CASE("an experiment killed with SIGKILL resumes to the same dataset as an uninterrupted run", "[experiment][resume]") {
    const fs::path root = fs::temp_directory_path() / ("rollsense-resume-" + std::to_string(getpid()));
    fs::remove_all(root);
    const fs::path full = root / "full", killed = root / "killed";

    REQUIRE(wait_exit(start(experiment(full, false))) == 0);
    REQUIRE(lines(full / "manifest.csv") == 1 + 9 * 3 * 4);

    pid_t pid = start(experiment(killed, false));
    // Kill it once some trials are durable, mid-run.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (lines(killed / "manifest.csv") < 1 + 10 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    kill(pid, SIGKILL);
    REQUIRE(wait_exit(pid) == 128 + SIGKILL);
    const auto before = lines(killed / "manifest.csv");
    INFO("trials on disk when killed: " << before - 1);
    CHECK(before < 1 + 9 * 3 * 4);  // it really was interrupted

    REQUIRE(wait_exit(start(experiment(killed, true))) == 0);
    CHECK(read_file(killed / "manifest.csv") == read_file(full / "manifest.csv"));
    CHECK(read_file(killed / "dataset-info.csv") == read_file(full / "dataset-info.csv"));
    std::size_t compared = 0;
    for (const auto& e : fs::directory_iterator(full / "trials")) {
        INFO(e.path().filename());
        CHECK(read_file(killed / "trials" / e.path().filename()) == read_file(e.path()));
        ++compared;
    }
    CHECK(compared == 9 * 3 * 4);
    // No temporaries left behind by the killed writer.
    for (const auto& e : fs::directory_iterator(killed / "trials"))
        CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
    fs::remove_all(root);
}

TEST_CASE("resuming with another seed is refused and changes nothing", "[experiment][resume]") {
    const fs::path out = fs::temp_directory_path() / ("rollsense-reseed-" + std::to_string(getpid()));
    fs::remove_all(out);
    auto args = experiment(out, false);
    args[6] = "runs=1";
    args[10] = "11";
    args.insert(args.end() - 1, {"--set", "objects=C1", "--set", "analyse=false"});
    REQUIRE(wait_exit(start(args)) == 0);
    const auto manifest = read_file(out / "manifest.csv");
    args[10] = "12";
    args.push_back("--resume");
    CHECK(wait_exit(start(args)) != 0);  // refused (the message names the seed to use)
    CHECK(read_file(out / "manifest.csv") == manifest);
    fs::remove_all(out);
}
