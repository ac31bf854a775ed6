// The live view end to end (issue 27): `rollsense run --live` on the emulated
// hand (the E-TRoll bus emulated on a pty, real time), headless Chromium on
// the page while the first trial rolls, and plain requests:
//   - the page receives and draws samples of the running trial (the counts it
//     writes into the DOM, rising; a screenshot with plotted pixels);
//   - a client that stops reading and one that is killed do not stall the run
//     (it ends with every trial saved);
//   - other paths get 404, other methods 405, a malformed request 400;
//   - [busy] a page that meets a full server (every client slot taken, the
//     server answers 503 with Retry-After) says so, waits and asks again, and
//     goes live once there is room: for its first fetch and for its stream.
// Run by tests/live/with_chromium.sh, which installs Chromium when it may.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <regex>
#include <sstream>
#include <thread>

#include "etroll_bus.hpp"
#include "http_client.hpp"
#include "live/http_server.hpp"
#include "png_image.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using rollsense::testing::connect_local;
using rollsense::testing::http_get;
using rollsense::testing::status_of;

namespace {

std::string read_file(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A number the page wrote into the element with this id (-1: not found).
long dom_count(const std::string& dom, const std::string& id) {
    std::smatch m;
    if (std::regex_search(dom, m, std::regex("id=\"" + id + "\"[^>]*>([0-9]+)<"))) return std::stol(m[1]);
    return -1;
}
long points_drawn(const std::string& dom) {
    std::smatch m;
    if (std::regex_search(dom, m, std::regex("id=\"plot-channels\"[^>]*data-points=\"([0-9]+)\""))) return std::stol(m[1]);
    return -1;
}
// The opening tag and the text of the element with this id ("" when there is none).
std::string element(const std::string& dom, const std::string& id) {
    std::smatch m;
    if (std::regex_search(dom, m, std::regex("<[a-z]+ id=\"" + id + "\"[^>]*>[^<]*"))) return m[0];
    return {};
}

// The command line of headless Chromium for `args` and `url`; its own log
// (dbus and GPU complaints in a container) goes to chromium.log, not into the
// DOM. At the lowest CPU priority where nice holds: its start-up takes every
// core for a moment. As root (which also needs --no-sandbox) Chromium sets its
// own threads back to nice 0, and its IO, compositor and display threads to
// -8, above the run's control loop: the run's bus is given the patience for
// that (start_run). Not SCHED_IDLE: beside other work on both cores the
// browser then got no time, and the run ended before the page had loaded.
std::string chromium(const fs::path& work, const std::string& args, const std::string& url) {
    const char* exe = std::getenv("ROLLSENSE_CHROMIUM");
    std::string c = "(nice -n 19 " + std::string(exe ? exe : "chromium") +
                    " --headless --disable-gpu --no-first-run --disable-background-networking --disable-sync"
                    " --disable-component-update --hide-scrollbars --window-size=1200,900 --user-data-dir=" +
                    (work / "chromium-profile").string();
    if (::geteuid() == 0) c += " --no-sandbox";  // Chromium's sandbox refuses to run as root
    return c + " " + args + " " + url + " 2>>" + (work / "chromium.log").string() + ")";
}

const std::string kEventsRequest = "GET /events HTTP/1.1\r\nHost: x\r\n\r\n";

// `rollsense run tests/live/live_trials.lua --live=0` on the emulated bus at
// `device` (its stderr in `log`), recording `trials` trials: the run's pid.
pid_t start_run(const fs::path& work, const fs::path& log, const std::string& device, int trials = 2) {
    const std::string exe = std::string(ROLLSENSE_BIN_DIR) + "/rollsense";
    const std::string script = std::string(ROLLSENSE_SOURCE_DIR) + "/tests/live/live_trials.lua";
    const std::string out = (work / "out").string();
    const std::string dxl = "dxl_device=" + device;
    // This tests the view, not the bus's deadlines: a reply timeout of 250 ms
    // (not 30) keeps a CI machine busy with other builds from failing the run,
    // and so does a Bus Watchdog of 2 s (not 500 ms). The browser's start-up
    // (see chromium()) and other work on both cores paused the control loop
    // and the emulator in this process, whose servos keep the watchdog's time,
    // by up to 580 ms (measured on a two-core machine): the watchdog tripped
    // and the run ended with a hardware fault. One that stops for good still
    // trips it; tests/dynamixel tests the watchdog itself.
    const std::string patience = "devices.hand.params.timeout_ms=250";
    const std::string watchdog = "devices.hand.params.bus_watchdog_ms=2000";
    const std::string count = "trials=" + std::to_string(trials);
    const pid_t run = ::fork();
    REQUIRE(run >= 0);
    if (run == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, 2);
        ::execl(exe.c_str(), exe.c_str(), "run", script.c_str(), "--profile", "etroll-emulated", "--set",
                dxl.c_str(), "--set", patience.c_str(), "--set", watchdog.c_str(), "--set", count.c_str(), "--out",
                out.c_str(), "--live=0", "--no-progress", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    return run;
}

// Kills the run at the end of the test unless it was waited for (pid 0).
struct Reap {
    pid_t pid;
    ~Reap() {
        if (pid > 0 && ::kill(pid, SIGKILL) == 0) ::waitpid(pid, nullptr, 0);
    }
};

// The address the run prints (port 0: any free one); port stays 0 if it prints none.
std::string wait_for_url(const fs::path& log, std::uint16_t& port) {
    for (int i = 0; i < 400; ++i) {
        std::smatch m;
        const auto text = read_file(log);
        if (std::regex_search(text, m, std::regex("live view: (http://127\\.0\\.0\\.1:([0-9]+)/)"))) {
            port = static_cast<std::uint16_t>(std::stoi(m[2]));
            return m[1];
        }
        std::this_thread::sleep_for(25ms);
    }
    return {};
}

// Whether a trial records (samples in the stream) within 90 s.
bool wait_for_samples(std::uint16_t port) {
    const auto give_up = Clock::now() + 90s;
    while (Clock::now() < give_up) {
        const int fd = connect_local(port);
        if (fd < 0) return false;
        (void)::send(fd, kEventsRequest.data(), kEventsRequest.size(), MSG_NOSIGNAL);
        const bool sampling =
            rollsense::testing::read_reply(fd, 1 << 16, 1000ms).find("event: sample") != std::string::npos;
        ::close(fd);
        if (sampling) return true;
        std::this_thread::sleep_for(200ms);
    }
    return false;
}

bool send_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = ::send(fd, data, size, MSG_NOSIGNAL);
        if (n <= 0) return false;
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

// Event streams that take every client slot of the server and read all they
// are sent, so that it keeps them: while they are open, it answers anyone
// else 503. Called from the relay's threads, so no Catch2 assertions: false
// when it could not within a minute.
class SlotHolders {
public:
    explicit SlotHolders(std::uint16_t port) : port_(port) {}
    ~SlotHolders() { release(); }

    bool take_all() {
        const auto give_up = Clock::now() + 60s;
        while (fds_.size() < static_cast<std::size_t>(rollsense::live::HttpServer::kMaxClients)) {
            if (Clock::now() > give_up) return false;
            const int fd = connect_local(port_);
            if (fd < 0) return false;
            std::string head;
            if (send_all(fd, kEventsRequest.data(), kEventsRequest.size()))
                while (head.find("\r\n\r\n") == std::string::npos) {
                    pollfd p{fd, POLLIN, 0};
                    char buf[4096];
                    const ssize_t n = ::poll(&p, 1, 5000) > 0 ? ::recv(fd, buf, sizeof buf, 0) : 0;
                    if (n <= 0) break;
                    head.append(buf, static_cast<std::size_t>(n));
                }
            if (status_of(head) != 200) {  // a slot not free yet (a request of the page ending): again
                ::close(fd);
                std::this_thread::sleep_for(100ms);
                continue;
            }
            fds_.push_back(fd);
            readers_.emplace_back([fd] {
                for (char buf[4096]; ::recv(fd, buf, sizeof buf, 0) > 0;) {
                }
            });
        }
        return true;
    }

    // Closes them and waits until the server has noticed (it checks every
    // 250 ms) and answers again.
    bool release() {
        if (fds_.empty()) return true;
        for (const int fd : fds_) ::shutdown(fd, SHUT_RDWR);
        for (auto& t : readers_) t.join();
        for (const int fd : fds_) ::close(fd);
        fds_.clear();
        readers_.clear();
        std::this_thread::sleep_for(1s);
        for (const auto give_up = Clock::now() + 30s; Clock::now() < give_up; std::this_thread::sleep_for(100ms))
            if (status_of(http_get(port_, "/info.json")) == 200) return true;
        return false;
    }

private:
    std::uint16_t port_;
    std::vector<int> fds_;
    std::vector<std::thread> readers_;
};

// A TCP relay between headless Chromium and the live view's server, so that
// the test chooses the moment the server is full: the page is loaded through
// it (its URLs are relative, so all its requests come this way), every byte
// passes unchanged both ways (the server's own answers, 503 included), and
// before forwarding a request it calls `gate` with the request's method and
// target, one at a time, which may take or free the server's slots first.
class Relay {
public:
    using Gate = std::function<void(const std::string& method, const std::string& target)>;

    Relay(std::uint16_t server, Gate gate) : server_(server), gate_(std::move(gate)) {
        listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t len = sizeof a;
        REQUIRE(::bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), len) == 0);
        REQUIRE(::listen(listen_fd_, 16) == 0);
        ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &len);
        port_ = ntohs(a.sin_port);
        acceptor_ = std::thread([this] { accept_loop(); });
    }
    ~Relay() {
        stopping_ = true;
        acceptor_.join();
        for (auto& t : connections_) t.join();
        ::close(listen_fd_);
    }

    std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }
    // The statuses the server answered the requests for `target` with, in order.
    std::vector<int> statuses(const std::string& target) {
        std::lock_guard lock(mutex_);
        std::vector<int> s;
        for (const auto& [t, status] : answers_)
            if (t == target) s.push_back(status);
        return s;
    }

private:
    void accept_loop() {
        while (!stopping_) {
            pollfd p{listen_fd_, POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0) continue;
            const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
            if (fd >= 0) connections_.emplace_back([this, fd] { relay(fd); });
        }
    }

    // One connection: its request head, the gate, then bytes both ways until
    // both ends have closed (a side's end of input is passed on as shutdown).
    void relay(int browser) {
        std::string head;
        char buf[16384];
        while (head.find("\r\n\r\n") == std::string::npos) {
            pollfd p{browser, POLLIN, 0};
            if (stopping_ || ::poll(&p, 1, 100) < 0) return (void)::close(browser);
            if (p.revents == 0) continue;  // a connection Chromium opened ahead, idle so far
            const ssize_t n = ::recv(browser, buf, sizeof buf, 0);
            if (n <= 0) return (void)::close(browser);
            head.append(buf, static_cast<std::size_t>(n));
        }
        std::istringstream line(head);
        std::string method, target;
        line >> method >> target;
        {
            std::lock_guard lock(gate_mutex_);
            gate_(method, target);
        }
        const int server = connect_local(server_);
        if (server < 0 || !send_all(server, head.data(), head.size())) {
            if (server >= 0) ::close(server);
            return (void)::close(browser);
        }
        pollfd p[2] = {{browser, POLLIN, 0}, {server, POLLIN, 0}};
        std::string answer;  // its first bytes, for the status
        while (!stopping_ && (p[0].fd >= 0 || p[1].fd >= 0)) {
            if (::poll(p, 2, 100) < 0) break;
            bool broken = false;
            for (int i = 0; i < 2 && !broken; ++i) {
                if (p[i].fd < 0 || p[i].revents == 0) continue;
                const int to = i == 0 ? server : browser;
                const ssize_t n = ::recv(p[i].fd, buf, sizeof buf, 0);
                if (n <= 0) {
                    ::shutdown(to, SHUT_WR);
                    p[i].fd = -1;
                    continue;
                }
                if (i == 1 && answer.size() < 12) {
                    answer.append(buf, static_cast<std::size_t>(n));
                    if (answer.size() >= 12) {
                        std::lock_guard lock(mutex_);
                        answers_.emplace_back(target, status_of(answer));
                    }
                }
                broken = !send_all(to, buf, static_cast<std::size_t>(n));
            }
            if (broken) break;
        }
        ::close(server);
        ::close(browser);
    }

    std::uint16_t server_;
    Gate gate_;
    int listen_fd_ = -1;
    std::uint16_t port_ = 0;
    std::atomic<bool> stopping_{false};
    std::mutex gate_mutex_, mutex_;
    std::vector<std::pair<std::string, int>> answers_;
    std::vector<std::thread> connections_;
    std::thread acceptor_;
};

}  // namespace

TEST_CASE("rollsense run --live: headless Chromium draws the running trial, clients cannot stall the run",
          "[live][browser]") {
    auto emu = etroll_bus::start();
    const rollsense::testing::TempDir tmp("rollsense-live");
    const fs::path log = tmp.path() / "run.txt";
    // Three trials of about 18 s: the page is loaded three times while it
    // records (with two, a loaded machine could see the run end before).
    const pid_t run = start_run(tmp.path(), log, emu->device(), 3);
    Reap reap_run{run};
    std::uint16_t port = 0;
    const std::string url = wait_for_url(log, port);
    INFO(read_file(log));
    REQUIRE(port != 0);

    // Only the page, its assets and the stream; never a file path.
    CHECK(status_of(http_get(port, "/")) == 200);
    CHECK(status_of(http_get(port, "/style.css")) == 200);
    CHECK(status_of(http_get(port, "/etc/passwd")) == 404);
    CHECK(status_of(http_get(port, "/../../etc/passwd")) == 404);
    CHECK(status_of(http_get(port, "/out/manifest.csv")) == 404);
    CHECK(status_of(http_get(port, "/", "POST")) == 405);
    CHECK(status_of(http_get(port, "/events", "PUT")) == 405);
    CHECK(status_of(rollsense::testing::http_exchange(port, "\x01\x02 nonsense\r\n\r\n")) == 400);

    // A client that stops reading, and one that is killed mid-stream.
    const int stalled = rollsense::testing::connect_local(port);
    REQUIRE(stalled >= 0);
    const int small = 4096;
    ::setsockopt(stalled, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    const std::string& events = kEventsRequest;
    REQUIRE(::send(stalled, events.data(), events.size(), MSG_NOSIGNAL) > 0);
    const pid_t killed = ::fork();
    REQUIRE(killed >= 0);
    if (killed == 0) {
        const int fd = rollsense::testing::connect_local(port);
        (void)::send(fd, events.data(), events.size(), MSG_NOSIGNAL);
        for (char buf[256];;)
            if (::recv(fd, buf, sizeof buf, 0) <= 0) ::_exit(0);
    }

    // Wait until the first trial records (samples in the stream).
    const bool sampling = wait_for_samples(port);
    ::kill(killed, SIGKILL);
    ::waitpid(killed, nullptr, 0);
    REQUIRE(sampling);

    // The page, twice (?events=N: it stops following the stream after N
    // events, so the headless browser can finish loading and dump it): it has
    // received samples of the present trial and drawn them, and the second
    // time, later in the run, holds a later sample.
    const auto snapshot = [&](std::size_t n, const std::string& what) {
        return chromium(tmp.path(), "--virtual-time-budget=10000 " + what, "'" + url + "?events=" +
                                                                             std::to_string(n) + "'");
    };
    auto dump = rollsense::testing::run_command(snapshot(60, "--dump-dom"));
    INFO(dump.output.substr(0, 4000));
    const long samples1 = dom_count(dump.output, "n-samples");
    const std::pair<long, long> latest1{dom_count(dump.output, "latest-trial"), dom_count(dump.output, "latest-n")};
    CHECK(dom_count(dump.output, "n-events") == 60);
    CHECK(samples1 > 0);
    CHECK(points_drawn(dump.output) > 0);
    CHECK(dump.output.find("waiting for the first trial") == std::string::npos);
    // The fingers in deg and the palm and the winch in mm, on one plot: its caption says both.
    CHECK(dump.output.find("joint positions (deg, mm)") != std::string::npos);
    const fs::path shot = tmp.path() / "shot.png";
    auto screenshot = rollsense::testing::run_command(snapshot(120, "--screenshot=" + shot.string()));
    INFO(screenshot.output << read_file(tmp.path() / "chromium.log"));
    REQUIRE(fs::exists(shot));
    const auto img = rollsense::test::read_png(shot);
    // The plot colours (saturated), not the page's white, black and greys.
    std::size_t plotted = 0;
    for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
        const int hi = std::max({img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]});
        const int lo = std::min({img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]});
        plotted += hi - lo > 60;
    }
    INFO("plotted pixels: " << plotted);
    CHECK(plotted > 500);
    if (const char* keep = std::getenv("ROLLSENSE_LIVE_SCREENSHOT"))
        fs::copy_file(shot, keep, fs::copy_options::overwrite_existing);
    auto dump2 = rollsense::testing::run_command(snapshot(60, "--dump-dom"));
    const std::pair<long, long> latest2{dom_count(dump2.output, "latest-trial"), dom_count(dump2.output, "latest-n")};
    INFO("latest sample (trial, index): " << latest1.first << "," << latest1.second << " then " << latest2.first
                                          << "," << latest2.second);
    CHECK(latest2 > latest1);

    // The run ends in its own time with all its trials, the stalled client
    // notwithstanding (it still holds its connection, reading nothing).
    int status = 0;
    pid_t ended = 0;
    const auto deadline = Clock::now() + 120s;
    while ((ended = ::waitpid(run, &status, WNOHANG)) == 0 && Clock::now() < deadline) std::this_thread::sleep_for(100ms);
    ::close(stalled);
    INFO(read_file(log));
    REQUIRE(ended == run);
    reap_run.pid = 0;
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    CHECK_THAT(read_file(log), Catch::Contains("done: 3 trials saved"));
}

// The server serves HttpServer::kMaxClients clients at once and answers any
// more with 503 and Retry-After: 2. A browser's EventSource gives up for good
// on such an answer, and fetch() resolves on it, so the page has to wait and
// ask again by itself. Chromium loads the page through a relay that takes
// every slot of the server (with streams that read) just before the page's
// first request for info.json or for the event stream, so that the server
// itself answers 503; in the second part it frees them when the page asks
// for the same target the third time; in the third, the page itself is
// refused once.
// Chromium's virtual time (--virtual-time-budget) runs the page's waits at
// once when nothing else is pending, so the test waits for nothing.
TEST_CASE("rollsense run --live: a page that finds every client slot taken says so, retries and goes live",
          "[live][browser][busy]") {
    auto emu = etroll_bus::start();
    const rollsense::testing::TempDir tmp("rollsense-live-busy");
    const fs::path log = tmp.path() / "run.txt";
    // Killed at the end: its trials do not matter here, only that it still
    // records when the page goes live, however slowly the browser starts
    // (with two trials, a loaded CI machine saw the run end first).
    Reap reap_run{start_run(tmp.path(), log, emu->device(), 1000)};
    std::uint16_t port = 0;
    wait_for_url(log, port);
    INFO(read_file(log));
    REQUIRE(port != 0);
    REQUIRE(wait_for_samples(port));
    const std::string most = std::to_string(rollsense::live::HttpServer::kMaxClients);

    // One run for both (sections would start it twice, and its first trial
    // records only some seconds after the start). While the server stays
    // full, the page says so and asks again every Retry-After seconds.
    {
        SlotHolders holders(port);
        std::atomic<bool> held{true};
        int asked = 0;
        Relay relay(port, [&](const std::string&, const std::string& target) {
            if (target == "/info.json" && ++asked == 1) held = holders.take_all();
        });
        // 10 s of the page's (virtual) time: about five tries 2 s apart.
        const auto dump = rollsense::testing::run_command(
            chromium(tmp.path(), "--virtual-time-budget=10000 --dump-dom", relay.url()));
        INFO(dump.output.substr(0, 4000));
        REQUIRE(held);
        const auto answers = relay.statuses("/info.json");
        CHECK(answers.size() >= 2);
        CHECK(answers.size() <= 10);
        CHECK(std::all_of(answers.begin(), answers.end(), [](int status) { return status == 503; }));
        const auto shown = element(dump.output, "notice");
        CHECK_THAT(shown, Catch::Contains("busy: " + most + " viewers at most, retrying in 2 s"));
        CHECK_THAT(shown, !Catch::Contains("hidden"));
        CHECK(dom_count(dump.output, "n-events") == 0);
    }

    // Once there is room, the page goes live: after a refused info.json and a
    // refused event stream.
    REQUIRE(wait_for_samples(port));
    {
        SlotHolders holders(port);
        std::atomic<bool> held{true};
        std::map<std::string, int> asked;
        Relay relay(port, [&](const std::string&, const std::string& target) {
            if (target != "/info.json" && target != "/events") return;
            const int n = ++asked[target];
            if (n == 1) held = held && holders.take_all();
            if (n == 3) held = held && holders.release();
        });
        const auto dump = rollsense::testing::run_command(
            chromium(tmp.path(), "--virtual-time-budget=30000 --dump-dom", "'" + relay.url() + "?events=60'"));
        INFO(dump.output.substr(0, 4000));
        REQUIRE(held);
        // info.json: refused, refused after 2 s, answered; the stream: refused
        // (EventSource closes for good), HEAD refused, HEAD answered 2 s later, the stream.
        CHECK(relay.statuses("/info.json") == std::vector<int>{503, 503, 200});
        CHECK(relay.statuses("/events") == std::vector<int>{503, 503, 200, 200});
        CHECK(dom_count(dump.output, "n-events") == 60);
        CHECK(dom_count(dump.output, "n-samples") > 0);
        CHECK(points_drawn(dump.output) > 0);
        CHECK(dump.output.find("waiting for the first trial") == std::string::npos);
        CHECK_THAT(element(dump.output, "notice"), Catch::Contains("hidden"));
    }

    // The page itself refused: the browser shows the server's short page,
    // which reloads itself after Retry-After, and then the page goes live (it
    // was plain text, to be reloaded by hand).
    REQUIRE(wait_for_samples(port));
    {
        SlotHolders holders(port);
        std::atomic<bool> held{true};
        int asked = 0;
        Relay relay(port, [&](const std::string&, const std::string& target) {
            if (target.rfind("/?", 0) != 0) return;
            if (++asked == 1) held = holders.take_all();
            if (asked == 2) held = held && holders.release();
        });
        const auto dump = rollsense::testing::run_command(
            chromium(tmp.path(), "--virtual-time-budget=30000 --dump-dom", "'" + relay.url() + "?events=60'"));
        INFO(dump.output.substr(0, 4000));
        REQUIRE(held);
        CHECK(relay.statuses("/?events=60") == std::vector<int>{503, 200});
        CHECK(dom_count(dump.output, "n-events") == 60);
        CHECK_THAT(element(dump.output, "notice"), Catch::Contains("hidden"));
    }
}
