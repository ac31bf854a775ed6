#include "live/http_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <linux/sockios.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "rollsense/log.hpp"

namespace rollsense::live {

namespace {

using Steady = std::chrono::steady_clock;

int remaining_ms(Steady::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Steady::now()).count();
    return left > 0 ? static_cast<int>(left) : 0;
}

// Everything, or false when the client takes nothing for kSendTimeoutMs or is gone.
bool send_all(int fd, std::string_view data) {
    while (!data.empty()) {
        pollfd p{fd, POLLOUT, 0};
        if (::poll(&p, 1, HttpServer::kSendTimeoutMs) <= 0 || (p.revents & (POLLERR | POLLHUP))) return false;
        const ssize_t n = ::send(fd, data.data(), data.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n < 0) {
            if (errno == EAGAIN || errno == EINTR) continue;
            return false;
        }
        data.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
}

// After a whole reply: the client gets to read it before the connection
// goes. Closing with bytes of its request unread (a body refused with 405 or
// 400, a request the 503 did not wait for) would reset the connection, and
// the reset can overtake the reply. Waits up to `wait_ms` for the client to close.
void close_after_reply(int fd, int wait_ms = HttpServer::kSendTimeoutMs) {
    ::shutdown(fd, SHUT_WR);
    const auto deadline = Steady::now() + std::chrono::milliseconds(wait_ms);
    char buf[4096];
    for (std::size_t drained = 0; drained < (1u << 20);) {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, remaining_ms(deadline)) <= 0) return;
        const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
        if (n <= 0) return;  // the client has closed: it has the reply
        drained += static_cast<std::size_t>(n);
    }
}

// Whether a stream's client has stopped reading. send() says nothing about
// it until the socket buffers are full (megabytes on loopback: minutes of a
// run's stream), so the stream watches what the client's end acknowledges:
// bytes waiting in the send queue (SIOCOUTQ: unsent or unacknowledged) with
// none of them acknowledged for kSendTimeoutMs mean its receive buffer is
// full and stays so. The check costs one ioctl per pass of the stream loop.
class ReadWatch {
public:
    void sent(std::size_t bytes) { expected_ += bytes; }
    bool stalled(int fd) {
        int waiting = 0;
        if (::ioctl(fd, SIOCOUTQ, &waiting) != 0) return false;  // not TCP: send_all's timeout still holds
        const auto now = Steady::now();
        const auto queued = static_cast<std::size_t>(waiting);
        if (queued == 0 || queued < expected_) progress_ = now;  // some were acknowledged
        expected_ = queued;
        return now - progress_ > std::chrono::milliseconds(HttpServer::kSendTimeoutMs);
    }

private:
    std::size_t expected_ = 0;  // what would wait had nothing been acknowledged since the last check
    Steady::time_point progress_ = Steady::now();
};

}  // namespace

Status HttpServer::check_address(const std::string& address) {
    in6_addr any{};  // large enough for either family
    if (::inet_pton(AF_INET, address.c_str(), &any) == 1 || ::inet_pton(AF_INET6, address.c_str(), &any) == 1) return {};
    return {ErrorCode::invalid_argument, "'" + address + "' is not an IPv4 or IPv6 address (e.g. 127.0.0.1 or ::1)"};
}

Result<std::unique_ptr<HttpServer>> HttpServer::start(const std::string& address, std::uint16_t port, Site site,
                                                      EventHub* hub, std::string_view port_option) {
    if (auto s = check_address(address); !s.ok()) return Error{s.code(), "live view: " + s.message()};
    sockaddr_storage ss{};
    socklen_t len = 0;
    int family = AF_INET;
    if (auto* a4 = reinterpret_cast<sockaddr_in*>(&ss); ::inet_pton(AF_INET, address.c_str(), &a4->sin_addr) == 1) {
        a4->sin_family = AF_INET;
        a4->sin_port = htons(port);
        len = sizeof(sockaddr_in);
    } else if (auto* a6 = reinterpret_cast<sockaddr_in6*>(&ss); ::inet_pton(AF_INET6, address.c_str(), &a6->sin6_addr) == 1) {
        a6->sin6_family = AF_INET6;
        a6->sin6_port = htons(port);
        len = sizeof(sockaddr_in6);
        family = AF_INET6;
    }
    const int fd = ::socket(family, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return Error{ErrorCode::io_error, std::string("live view: socket: ") + std::strerror(errno)};
    const int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(fd, reinterpret_cast<sockaddr*>(&ss), len) != 0 || ::listen(fd, 16) != 0) {
        const std::string why = std::strerror(errno);
        ::close(fd);
        return Error{ErrorCode::io_error, "live view: cannot listen on " + address + " port " + std::to_string(port) +
                                              ": " + why + " (choose another with " + std::string(port_option) + ")"};
    }
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&ss), &len);
    const std::uint16_t bound = ntohs(family == AF_INET ? reinterpret_cast<sockaddr_in*>(&ss)->sin_port
                                                        : reinterpret_cast<sockaddr_in6*>(&ss)->sin6_port);
    return std::unique_ptr<HttpServer>(new HttpServer(fd, address, bound, std::move(site), hub));
}

HttpServer::HttpServer(int fd, std::string address, std::uint16_t port, Site site, EventHub* hub)
    : listen_fd_(fd), address_(std::move(address)), port_(port), site_(std::move(site)), hub_(hub) {
    acceptor_ = std::thread([this] { accept_loop(); });
}

HttpServer::~HttpServer() {
    stopping_ = true;
    if (acceptor_.joinable()) acceptor_.join();
    std::lock_guard lock(threads_mutex_);
    for (auto& c : clients_)
        if (c.thread.joinable()) c.thread.join();
    ::close(listen_fd_);
}

// 0.0.0.0, ::, or another spelling of either.
bool HttpServer::listens_everywhere() const {
    in_addr a4{};
    in6_addr a6{};
    if (::inet_pton(AF_INET, address_.c_str(), &a4) == 1) return a4.s_addr == htonl(INADDR_ANY);
    return ::inet_pton(AF_INET6, address_.c_str(), &a6) == 1 && IN6_IS_ADDR_UNSPECIFIED(&a6);
}

std::string HttpServer::where() const {
    if (!listens_everywhere()) return url();
    return url() + " (listening on every address of this machine: from another, use its name or address)";
}

std::string HttpServer::url() const {
    // Listening on every address, it is reached on this machine at its loopback one.
    const bool v6_any = address_.find(':') != std::string::npos;
    const std::string host = !listens_everywhere() ? address_ : v6_any ? "::1" : "127.0.0.1";
    const bool v6 = host.find(':') != std::string::npos;
    return "http://" + (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port_) + "/";
}

void HttpServer::accept_loop() {
    while (!stopping_) {
        pollfd p{listen_fd_, POLLIN, 0};
        if (::poll(&p, 1, 100) <= 0) continue;
        const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (fd < 0) continue;
        std::lock_guard lock(threads_mutex_);
        clients_.remove_if([](Client& c) {  // finished clients leave the list
            if (!c.done) return false;
            c.thread.join();
            return true;
        });
        if (active_ >= kMaxClients) {
            // Answered before the request is read, so for the page and the page's own requests alike: a browser
            // shows it and reloads by itself (the refresh); the page's script reads the status and Retry-After.
            const std::string again = std::to_string(kRetryAfterS);
            (void)send_all(fd, http_response(503, "text/html; charset=utf-8",
                                             "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
                                             "<meta http-equiv=\"refresh\" content=\"" + again + "\">"
                                             "<title>rollsense live view: busy</title></head><body><p>" +
                                                 std::to_string(kMaxClients) +
                                                 " viewers at once at most: close another viewer of this run; this "
                                                 "page tries again every " + again +
                                                 " s (a viewer that stops reading leaves within seconds)</p></body>"
                                                 "</html>\n",
                                             "Retry-After: " + again + "\r\n"));
            close_after_reply(fd, 100);  // briefly: the acceptor waits meanwhile
            ::close(fd);
            continue;
        }
        ++active_;
        auto& c = clients_.emplace_back();
        c.thread = std::thread([this, fd, &c] {
            serve(fd);
            ::close(fd);
            --active_;
            c.done = true;
        });
    }
}

void HttpServer::serve(int fd) {
    std::string received;
    const auto deadline = Steady::now() + std::chrono::milliseconds(kRequestTimeoutMs);
    ParsedRequest parsed;
    while (!stopping_) {
        pollfd p{fd, POLLIN, 0};
        const int ready = ::poll(&p, 1, std::min(remaining_ms(deadline), 100));
        if (ready < 0 && errno != EINTR) return;
        if (ready > 0) {
            char buf[2048];
            const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
            if (n <= 0) return;  // gone before asking anything
            received.append(buf, static_cast<std::size_t>(n));
            parsed = parse_request(received);
            if (parsed.state != ParsedRequest::State::incomplete) break;
        }
        if (remaining_ms(deadline) == 0) return;  // too slow to ask: dropped without an answer
    }
    if (parsed.state == ParsedRequest::State::malformed) {
        if (send_all(fd, http_response(400, "text/plain; charset=utf-8", "malformed request: " + parsed.error + "\n")))
            close_after_reply(fd);
        return;
    }
    if (parsed.state != ParsedRequest::State::complete) return;
    Reply reply = site_(parsed.request);
    if (!reply.stream) {
        if (send_all(fd, reply.bytes)) close_after_reply(fd);
        return;
    }
    stream(fd);
}

void HttpServer::stream(int fd) {
    // A small send buffer bounds what waits for a client (the kernel's own
    // grows to megabytes), so one that reads nothing soon blocks send_all.
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &kStreamSendBuffer, sizeof kStreamSendBuffer);
    if (!send_all(fd, sse_head())) return;
    auto batch = hub_->join();
    std::string out;
    auto last_sent = Steady::now();
    ReadWatch watch;
    const auto drop = [this] {
        ++clients_dropped_;
        log_info("live", "a viewer was dropped (too slow or gone)");
    };
    for (;;) {
        out.clear();
        for (const auto& e : batch.events) out += e;
        if (batch.missed > 0) out += sse_event("lag", "{\"missed\":" + std::to_string(batch.missed) + "}");
        // A comment now and then finds a client that went away without a word.
        if (out.empty() && Steady::now() - last_sent > std::chrono::seconds(5)) out = ": alive\n\n";
        if (!out.empty()) {
            if (!send_all(fd, out)) return drop();
            watch.sent(out.size());
            last_sent = Steady::now();
        }
        if (watch.stalled(fd)) return drop();
        if ((batch.closed && batch.events.empty()) || stopping_) return;
        batch = hub_->take(batch.next, std::chrono::milliseconds(250));
        // A client that has closed its end leaves now, not at the next event
        // (between trials there may be none for a while): its slot is free.
        pollfd p{fd, POLLRDHUP, 0};
        if (::poll(&p, 1, 0) > 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR))) return;
    }
}

}  // namespace rollsense::live
