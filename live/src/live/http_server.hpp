// The live view's HTTP server: plain POSIX sockets with timeouts (so a slow
// or vanished client is dropped, never waited for), Boost.Beast's parser for
// requests (http.hpp), a thread per client up to kMaxClients. It serves only
// what its Site answers; the event stream comes from an EventHub.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "live/event_hub.hpp"
#include "live/http.hpp"
#include "rollsense/status.hpp"

namespace rollsense::live {

// What a request gets: a whole response, or (stream) the event stream.
struct Reply {
    std::string bytes;
    bool stream = false;
};
using Site = std::function<Reply(const Request&)>;

class HttpServer {
public:
    // Listen on address:port (port 0: any free one). The hub may be null (no /events).
    // port_option: the caller's option for another port, named when this one is taken.
    static Result<std::unique_ptr<HttpServer>> start(const std::string& address, std::uint16_t port, Site site,
                                                      EventHub* hub, std::string_view port_option = "--live=PORT");
    // Whether `address` is a numeric IPv4 or IPv6 address start() can listen on (checked before warning about it).
    static Status check_address(const std::string& address);
    ~HttpServer();  // stops accepting, ends every client and waits for their threads

    std::uint16_t port() const { return port_; }
    // Where to browse it on this machine (the loopback address when it listens on every address).
    std::string url() const;
    // url(), and when it listens on every address (0.0.0.0, ::) a word that other machines reach it too.
    std::string where() const;
    bool listens_everywhere() const;
    std::uint64_t clients_dropped() const { return clients_dropped_; }  // too slow or gone
    int active_clients() const { return active_; }

    static constexpr int kMaxClients = 8;
    static constexpr int kRetryAfterS = 2;          // a client refused for want of room asks again after this
    static constexpr int kRequestTimeoutMs = 5000;  // to send the request head
    static constexpr int kSendTimeoutMs = 2000;     // a client that takes no data this long is dropped
    static constexpr int kStreamSendBuffer = 64 * 1024;  // SO_SNDBUF of an event stream (the kernel doubles it)

private:
    HttpServer(int fd, std::string address, std::uint16_t port, Site site, EventHub* hub);
    void accept_loop();
    void serve(int fd);
    void stream(int fd);

    int listen_fd_;
    std::string address_;
    std::uint16_t port_;
    Site site_;
    EventHub* hub_;
    std::atomic<bool> stopping_{false};
    std::atomic<int> active_{0};
    std::atomic<std::uint64_t> clients_dropped_{0};
    std::mutex threads_mutex_;
    struct Client {
        std::thread thread;
        std::atomic<bool> done{false};
    };
    std::list<Client> clients_;
    std::thread acceptor_;
};

}  // namespace rollsense::live
