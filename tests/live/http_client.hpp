// A bare HTTP client for the live view's tests: raw bytes to 127.0.0.1:port,
// everything the server sends back until it closes (or a timeout).
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>

namespace rollsense::testing {

inline int connect_local(std::uint16_t port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

// Read until the server closes, `limit` bytes arrive, or nothing comes for `quiet`.
inline std::string read_reply(int fd, std::size_t limit = 1 << 20,
                              std::chrono::milliseconds quiet = std::chrono::milliseconds(3000)) {
    std::string out;
    char buf[4096];
    while (out.size() < limit) {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(quiet.count())) <= 0) break;
        const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
        if (n <= 0) break;
        out.append(buf, static_cast<std::size_t>(n));
    }
    return out;
}

// Send `request` as it is and return the whole reply ("" if no connection).
inline std::string http_exchange(std::uint16_t port, const std::string& request, std::size_t limit = 1 << 20) {
    const int fd = connect_local(port);
    if (fd < 0) return {};
    (void)::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
    auto reply = read_reply(fd, limit);
    ::close(fd);
    return reply;
}

inline std::string http_get(std::uint16_t port, const std::string& path, const std::string& method = "GET") {
    return http_exchange(port, method + " " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
}

// "HTTP/1.1 404 Not Found..." -> 404 (0 when there is no status line).
inline int status_of(const std::string& reply) {
    if (reply.rfind("HTTP/1.1 ", 0) != 0 || reply.size() < 12) return 0;
    return std::stoi(reply.substr(9, 3));
}

}  // namespace rollsense::testing
