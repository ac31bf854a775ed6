// A pseudo-terminal pair: the master end for an emulated device, the slave
// path for the client that opens it like a real serial port.
#pragma once

#include <string>

#include "rollsense/status.hpp"

namespace rollsense::hal {

class PtyPair {
public:
    PtyPair() = default;
    ~PtyPair();
    PtyPair(const PtyPair&) = delete;
    PtyPair& operator=(const PtyPair&) = delete;
    PtyPair(PtyPair&& other) noexcept;
    PtyPair& operator=(PtyPair&& other) noexcept;

    // Open a new pair with the slave already in raw mode. The pair keeps a
    // descriptor on the slave open itself, so the master never reads EIO while
    // no client has the slave open (clients come and go between test cases).
    static Result<PtyPair> open();

    int master_fd() const noexcept { return master_; }
    // The pair's own descriptor on the slave: termios belongs to the tty, so
    // this reads the line settings (e.g. the baud rate) a client has set.
    int slave_fd() const noexcept { return slave_keepalive_; }
    const std::string& slave_path() const noexcept { return slave_path_; }

    void close() noexcept;

private:
    int master_ = -1;
    int slave_keepalive_ = -1;
    std::string slave_path_;
};

// Put a tty descriptor in raw 8N1 mode, no flow control, VMIN=0/VTIME=0.
Status make_raw(int fd, const std::string& name);

}  // namespace rollsense::hal
