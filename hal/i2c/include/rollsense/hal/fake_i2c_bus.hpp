// An in-process I2C bus with attached device models, for tests and for running
// without hardware.
//
// It follows the wire, byte by byte, rather than mapping (address → register
// file): every attached device sees every address byte (a TakkStrip's ATtiny
// acts on the address alone), ACKs only what it wants, and when several
// devices answer one read their bytes combine as wired-AND (open-drain SDA) —
// so a host that leaves two barometers selected gets the garbage real
// hardware would give it. Time is virtual: transfers take their duration at
// the bus clock rate and sleep_for() advances the clock, so device models can
// enforce timing rules (e.g. conversion time) deterministically.
//
// Buses are shared process-wide by name (FakeI2cBus::get("strip")) so a test
// and a plugin loaded from a profile with bus = "fake:strip" see the same bus.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "rollsense/hal/i2c.hpp"

namespace rollsense::hal {

// A device model on a FakeI2cBus. `time` is the bus's virtual clock in seconds.
class I2cDevice {
public:
    virtual ~I2cDevice() = default;
    // A START (or repeated START) and address byte. Return true to ACK.
    virtual bool on_address(std::uint8_t address, bool read, double time) = 0;
    // A data byte written to this device (it ACKed the address). Return true to ACK.
    virtual bool on_write_byte(std::uint8_t value, double time) = 0;
    // The next byte this device drives for a read it ACKed.
    virtual std::uint8_t on_read_byte(double time) = 0;
    // STOP: the end of the transfer.
    virtual void on_stop(double time) = 0;
};

// One message on the wire, as the fake saw it.
struct I2cLogEntry {
    enum class Kind { quick, write, read };
    double time = 0.0;       // bus clock at the START of this message
    Kind kind = Kind::write;
    bool read_bit = false;   // the R/W bit (quick commands have one too)
    std::uint8_t address = 0;
    bool acked = false;      // someone ACKed the address byte
    bool repeated_start = false;  // this message followed another without a STOP
    std::vector<std::uint8_t> data;  // bytes that actually moved
};

class FakeI2cBus final : public I2cBus {
public:
    // The bus of that name, created on first use (process-wide).
    static std::shared_ptr<FakeI2cBus> get(const std::string& name);

    explicit FakeI2cBus(std::string name);

    const std::string& name() const override { return spec_; }
    I2cFunctionality functionality() const override;
    Status transfer(std::span<I2cMessage> messages) override;
    Status quick(std::uint8_t address, bool read) override;
    void sleep_for(std::chrono::microseconds duration) override;

    // ---- test / setup side ----
    void attach(std::shared_ptr<I2cDevice> device);
    void detach(const std::shared_ptr<I2cDevice>& device);
    void detach_all();
    // Virtual time in seconds since the bus was created.
    double now() const;
    // SCL frequency used to charge transfer time (default 400 kHz).
    void set_clock_hz(double hz);
    // Pretend to be an adapter with other capabilities (e.g. no SMBus quick).
    void set_functionality(I2cFunctionality f);
    // The next `count` transfers/quick commands fail with this errno before any
    // byte moves (EIO, ETIMEDOUT, EAGAIN, ...), as a flaky bus would.
    void inject_errno(int err, int count = 1);
    std::vector<I2cLogEntry> log() const;
    void clear_log();
    // Restore a fresh bus: no devices, empty log, no injected errors, t unchanged.
    void reset();

private:
    Status transfer_locked(std::span<I2cMessage> messages);
    void charge_bits(double bits);
    void stop_all();

    std::string spec_;  // "fake:<name>"
    mutable std::mutex mutex_;
    std::vector<std::shared_ptr<I2cDevice>> devices_;
    std::vector<I2cLogEntry> log_;
    double now_ = 0.0;
    double clock_hz_ = 400e3;
    I2cFunctionality funcs_;
    int injected_errno_ = 0;
    int injected_count_ = 0;
};

}  // namespace rollsense::hal
