// The serial backend against the other end of a real pseudo-terminal.
#include <catch2/catch.hpp>

#include <poll.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <string>
#include <vector>

#include "rollsense/hal/baud_rate.hpp"
#include "rollsense/hal/pty_pair.hpp"
#include "rollsense/hal/serial_port.hpp"

using namespace rollsense;
using namespace rollsense::hal;
using namespace std::chrono_literals;

namespace {

std::vector<std::uint8_t> read_master(int fd, std::size_t n) {
    std::vector<std::uint8_t> out;
    for (int tries = 0; tries < 200 && out.size() < n; ++tries) {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 10) <= 0) continue;
        std::array<std::uint8_t, 256> buf{};
        const ssize_t r = ::read(fd, buf.data(), buf.size());
        if (r > 0) out.insert(out.end(), buf.begin(), buf.begin() + r);
    }
    return out;
}

}  // namespace

TEST_CASE("bytes cross a pty in both directions unchanged (raw mode: no echo, no CR/LF mangling)") {
    auto pty = PtyPair::open();
    REQUIRE(pty.ok());
    auto port = SerialPort::open(pty->slave_path(), 57600);
    INFO((port.ok() ? std::string() : port.error().message));
    REQUIRE(port.ok());

    // Every byte value, including ones a cooked tty would eat (^C, ^S, CR, DEL).
    std::vector<std::uint8_t> all(256);
    for (int i = 0; i < 256; ++i) all[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
    REQUIRE(port->write_all(all).ok());
    CHECK(read_master(pty->master_fd(), all.size()) == all);

    REQUIRE(::write(pty->master_fd(), all.data(), all.size()) == 256);
    std::vector<std::uint8_t> got(256);
    REQUIRE(port->read_exact(got, 500ms).ok());
    CHECK(got == all);
}

TEST_CASE("a read with nothing to read returns after its timeout with zero bytes") {
    auto pty = PtyPair::open();
    REQUIRE(pty.ok());
    auto port = SerialPort::open(pty->slave_path(), 115200);
    REQUIRE(port.ok());
    std::array<std::uint8_t, 8> buf{};
    auto r = port->read_some(buf, 20ms);
    REQUIRE(r.ok());
    CHECK(*r == 0);

    const std::uint8_t two[2] = {1, 2};
    REQUIRE(::write(pty->master_fd(), two, 2) == 2);
    auto st = port->read_exact(buf, 50ms);
    CHECK(st.code() == ErrorCode::timeout);
    CHECK(st.message().find("got 2 of 8 bytes") != std::string::npos);
}

TEST_CASE("discard_input drops stale bytes") {
    auto pty = PtyPair::open();
    REQUIRE(pty.ok());
    auto port = SerialPort::open(pty->slave_path(), 57600);
    REQUIRE(port.ok());
    const std::uint8_t stale[3] = {9, 9, 9};
    REQUIRE(::write(pty->master_fd(), stale, 3) == 3);
    // Let the pty move the bytes across before flushing.
    std::array<std::uint8_t, 1> peek{};
    pollfd p{port->fd(), POLLIN, 0};
    REQUIRE(::poll(&p, 1, 500) == 1);
    REQUIRE(port->discard_input().ok());
    auto r = port->read_some(peek, 10ms);
    REQUIRE(r.ok());
    CHECK(*r == 0);
}

TEST_CASE("standard rates map to termios codes, others go through termios2") {
    CHECK(standard_speed_code(57600).has_value());
    CHECK(standard_speed_code(1000000).has_value());
    CHECK(standard_speed_code(4000000).has_value());
    CHECK_FALSE(standard_speed_code(4500000).has_value());
    CHECK_FALSE(standard_speed_code(250000).has_value());

    auto pty = PtyPair::open();
    REQUIRE(pty.ok());
    auto port = SerialPort::open(pty->slave_path(), 250000);
    INFO((port.ok() ? std::string() : port.error().message));
    REQUIRE(port.ok());
    auto applied = query_baud(port->fd());
    REQUIRE(applied.ok());
    CHECK(*applied == 250000u);
    REQUIRE(port->set_baud(1000000).ok());
    CHECK(*query_baud(port->fd()) == 1000000u);
    CHECK(port->baud() == 1000000u);
    CHECK(port->byte_time() == std::chrono::nanoseconds(10000));
}

TEST_CASE("opening a missing device names it and says what to check") {
    auto port = SerialPort::open("/dev/ttyUSB-does-not-exist", 57600);
    REQUIRE_FALSE(port.ok());
    CHECK(port.error().code == ErrorCode::not_found);
    CHECK(port.error().message.find("/dev/ttyUSB-does-not-exist") != std::string::npos);
    CHECK(port.error().message.find("plugged") != std::string::npos);
}

TEST_CASE("a regular file is refused as a serial port") {
    char path[] = "/tmp/rollsense-not-a-tty-XXXXXX";
    const int fd = ::mkstemp(path);
    REQUIRE(fd >= 0);
    ::close(fd);
    auto port = SerialPort::open(path, 57600);
    ::unlink(path);
    REQUIRE_FALSE(port.ok());
    CHECK(port.error().message.find("not a terminal") != std::string::npos);
    CHECK(port.error().message.find("name the adapter's serial port") != std::string::npos);
    // Review hw item 5: the profile's mistake (exit 3), not a file that could not be read or written (exit 5).
    CHECK(port.error().code == ErrorCode::not_found);
    auto null = SerialPort::open("/dev/null", 57600);
    REQUIRE_FALSE(null.ok());
    CHECK(null.error().code == ErrorCode::not_found);
}

TEST_CASE("a rate of zero is refused") {
    auto pty = PtyPair::open();
    REQUIRE(pty.ok());
    auto port = SerialPort::open(pty->slave_path(), 0);
    REQUIRE_FALSE(port.ok());
    CHECK(port.error().code == ErrorCode::invalid_argument);
}

// Hardware review: TIOCEXCL does not stop root, so a second run as root drove the servos beside the first, and both
// failed with bus errors that named no other program. The port is locked (flock) too, and the holder named.
TEST_CASE("a port another holder has open is refused, naming the holder, and free again once it is closed") {
    auto pty = PtyPair::open();
    REQUIRE(pty.ok());
    auto first = SerialPort::open(pty->slave_path(), 57600);
    REQUIRE(first.ok());
    auto second = SerialPort::open(pty->slave_path(), 57600);
    REQUIRE_FALSE(second.ok());
    INFO(second.error().message);
    CHECK_THAT(second.error().message, Catch::Contains(pty->slave_path() + ": cannot open serial port: ") &&
                                           Catch::Contains("another program has"));
    // The holder is named from its lock, whichever refused the open (TIOCEXCL first, but for root); here it is this
    // very process, as two devices of one profile on one port would be.
    CHECK_THAT(second.error().message, Catch::Contains("(this process: two devices on one port?)"));
    if (::geteuid() == 0) CHECK_THAT(second.error().message, Catch::Contains("stop it first"));
    first->close();
    CHECK(SerialPort::open(pty->slave_path(), 57600).ok());
}
