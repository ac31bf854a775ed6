// Bus conveniences, the spec parser and the errno → Error mapping shared by
// the Linux backend and the fake (so tests see the messages users will see).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "rollsense/hal/fake_i2c_bus.hpp"
#include "rollsense/hal/i2c.hpp"

namespace rollsense::hal {

Status I2cBus::write(std::uint8_t address, std::span<const std::uint8_t> bytes) {
    // i2c_msg.buf is not const; copy rather than cast the caller's constness away.
    std::vector<std::uint8_t> copy(bytes.begin(), bytes.end());
    I2cMessage msg{address, false, copy};
    return transfer(std::span<I2cMessage>(&msg, 1));
}

Status I2cBus::read(std::uint8_t address, std::span<std::uint8_t> out) {
    I2cMessage msg{address, true, out};
    return transfer(std::span<I2cMessage>(&msg, 1));
}

Status I2cBus::write_read(std::uint8_t address, std::span<const std::uint8_t> bytes, std::span<std::uint8_t> out) {
    std::vector<std::uint8_t> copy(bytes.begin(), bytes.end());
    I2cMessage msgs[2] = {{address, false, copy}, {address, true, out}};
    return transfer(msgs);
}

std::string format_i2c_address(std::uint8_t address) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%02x", static_cast<unsigned>(address));
    return buf;
}

Error i2c_transfer_error(const std::string& bus, std::uint8_t address, const char* operation, int err) {
    const std::string where = "i2c " + bus + ", address " + format_i2c_address(address) + ", " + operation + ": ";
    switch (err) {
        case ENXIO:
        case EREMOTEIO:
            // Adapters differ on which of the two a NACK on the address byte gives.
            return {ErrorCode::hardware_fault,
                    where + "no acknowledge (NACK): nothing answered at this address — check that the device is "
                            "powered, wired (SDA/SCL/GND), and (on a TakkStrip) selected"};
        case ETIMEDOUT:
            return {ErrorCode::timeout, where + "bus timed out: SDA or SCL is held low — check the pull-ups and "
                                                "for a device stuck mid-transfer (power-cycle it)"};
        case EAGAIN:
            return {ErrorCode::io_error, where + "lost arbitration or bus busy: another master is active"};
        case EOPNOTSUPP:
            return {ErrorCode::unsupported, where + "the adapter does not support this kind of transfer"};
        case ENODEV:
            return {ErrorCode::not_found, where + "the adapter has gone (unplugged or its driver unloaded)"};
        case EBUSY:
            return {ErrorCode::io_error, where + "address in use by a kernel driver: unbind it "
                                                 "(echo <bus>-00xx > /sys/bus/i2c/devices/<dev>/driver/unbind)"};
        case EIO:
            return {ErrorCode::io_error, where + "I/O error (bus error, or a NACK on adapters that report it "
                                                 "this way) — check wiring and pull-ups"};
        default:
            return {ErrorCode::io_error, where + std::strerror(err)};
    }
}

Result<std::shared_ptr<I2cBus>> open_i2c_bus(const std::string& spec) {
    constexpr std::string_view fake_prefix = "fake:";
    if (spec.rfind(fake_prefix, 0) == 0) {
        const std::string name = spec.substr(fake_prefix.size());
        if (name.empty())
            return Error{ErrorCode::invalid_argument, "I2C bus spec 'fake:' needs a name, e.g. 'fake:strip'"};
        return std::shared_ptr<I2cBus>(FakeI2cBus::get(name));
    }
    if (!spec.empty() && spec.find_first_not_of("0123456789") == std::string::npos)
        return open_linux_i2c_bus("/dev/i2c-" + spec);
    if (!spec.empty() && spec[0] == '/') return open_linux_i2c_bus(spec);
    return Error{ErrorCode::invalid_argument,
                 "I2C bus spec '" + spec + "' not understood: use /dev/i2c-N, N, or fake:<name>"};
}

}  // namespace rollsense::hal
