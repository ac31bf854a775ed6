// I2C bus access: the transfers the TakkStrip and its MPL115A2 barometers need.
//
// Two implementations share this interface:
//   - a Linux backend over i2c-dev (/dev/i2c-N): ioctl(I2C_RDWR) for combined
//     transfers, ioctl(I2C_SMBUS) for quick commands, ioctl(I2C_FUNCS) to refuse
//     what the adapter cannot do before trying it;
//   - FakeI2cBus (fake_i2c_bus.hpp), an in-process bus onto which device models
//     attach, for tests and for running without hardware.
// Both report failures the same way: a typed Error whose message names the bus,
// the 7-bit address, what failed and what to check.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "rollsense/status.hpp"

namespace rollsense::hal {

// What an adapter supports (the I2C_FUNCS bits this code relies on).
struct I2cFunctionality {
    bool combined_transfers = false;  // I2C_FUNC_I2C: I2C_RDWR with repeated START between messages
    bool smbus_quick = false;         // I2C_FUNC_SMBUS_QUICK: address-only transfers (TakkStrip select)
    unsigned long raw = 0;            // the whole I2C_FUNCS word, for diagnostics
};

// One message of a combined transfer. Writes send `data`; reads fill it.
struct I2cMessage {
    std::uint8_t address = 0;  // 7-bit address
    bool read = false;
    std::span<std::uint8_t> data;
};

// The kernel's limit on messages per I2C_RDWR call (I2C_RDWR_IOCTL_MAX_MSGS).
inline constexpr std::size_t kI2cMaxMessages = 42;

class I2cBus {
public:
    virtual ~I2cBus() = default;

    // "/dev/i2c-1" or "fake:<name>": used in every error message.
    virtual const std::string& name() const = 0;
    virtual I2cFunctionality functionality() const = 0;

    // One combined transfer: START, the messages separated by repeated STARTs,
    // one STOP at the end. The first failing byte aborts the rest.
    virtual Status transfer(std::span<I2cMessage> messages) = 0;

    // SMBus quick command: START, address byte with the R/W bit, STOP — no data.
    // read=false is a "quick write". The TakkStrip's ATtiny acts on this alone.
    virtual Status quick(std::uint8_t address, bool read) = 0;

    // Wait on the bus's own clock. A real bus sleeps; the fake advances its
    // virtual clock, which is what its device models see (so conversion-time
    // rules are checked deterministically, without wall-clock thresholds).
    virtual void sleep_for(std::chrono::microseconds duration) = 0;

    // Conveniences over transfer()/quick().
    Status write(std::uint8_t address, std::span<const std::uint8_t> bytes);
    Status read(std::uint8_t address, std::span<std::uint8_t> out);
    // Write (usually a register pointer), repeated START, read — one transfer.
    Status write_read(std::uint8_t address, std::span<const std::uint8_t> bytes, std::span<std::uint8_t> out);
    Status quick_write(std::uint8_t address) { return quick(address, false); }
    Status quick_read(std::uint8_t address) { return quick(address, true); }
};

// Open a bus by spec:
//   "/dev/i2c-N" or "N"  → the Linux i2c-dev backend
//   "fake:<name>"        → the process-wide fake bus of that name (FakeI2cBus::get)
Result<std::shared_ptr<I2cBus>> open_i2c_bus(const std::string& spec);

// Open the Linux backend directly (used by open_i2c_bus).
Result<std::shared_ptr<I2cBus>> open_linux_i2c_bus(const std::string& device_path);

// "0x60"
std::string format_i2c_address(std::uint8_t address);

// The error both backends return for a failed transfer: `err` is an errno
// value as i2c-dev reports it (ENXIO / EREMOTEIO = NACK, ETIMEDOUT, EIO, ...).
Error i2c_transfer_error(const std::string& bus, std::uint8_t address, const char* operation, int err);

}  // namespace rollsense::hal
