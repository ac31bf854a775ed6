#include "rollsense/hal/fake_i2c_bus.hpp"

#include <algorithm>
#include <cerrno>
#include <map>

namespace rollsense::hal {
namespace {
// The functionality word a typical SoC controller reports (I2C | SMBUS_EMUL).
constexpr unsigned long kDefaultFuncs = 0x00000001UL | 0x0eff0008UL;
}  // namespace

std::shared_ptr<FakeI2cBus> FakeI2cBus::get(const std::string& name) {
    static std::mutex registry_mutex;
    static std::map<std::string, std::shared_ptr<FakeI2cBus>> registry;
    std::lock_guard lock(registry_mutex);
    auto& slot = registry[name];
    if (!slot) slot = std::make_shared<FakeI2cBus>(name);
    return slot;
}

FakeI2cBus::FakeI2cBus(std::string name) : spec_("fake:" + std::move(name)) {
    funcs_.raw = kDefaultFuncs;
    funcs_.combined_transfers = true;
    funcs_.smbus_quick = true;
}

I2cFunctionality FakeI2cBus::functionality() const {
    std::lock_guard lock(mutex_);
    return funcs_;
}

void FakeI2cBus::charge_bits(double bits) { now_ += bits / clock_hz_; }

void FakeI2cBus::stop_all() {
    charge_bits(1);  // STOP
    for (auto& d : devices_) d->on_stop(now_);
}

Status FakeI2cBus::transfer(std::span<I2cMessage> messages) {
    if (messages.empty()) return {};
    if (messages.size() > kI2cMaxMessages)
        return Status(ErrorCode::invalid_argument, "i2c " + spec_ + ": " + std::to_string(messages.size()) +
                                                       " messages in one transfer, the kernel allows at most 42");
    std::lock_guard lock(mutex_);
    if (!funcs_.combined_transfers)
        return Status(ErrorCode::unsupported,
                      "i2c " + spec_ + ": the adapter does not support plain I2C transfers (I2C_FUNC_I2C); "
                                       "it is an SMBus-only controller — use another I2C bus");
    return transfer_locked(messages);
}

Status FakeI2cBus::transfer_locked(std::span<I2cMessage> messages) {
    if (injected_count_ > 0) {
        --injected_count_;
        return i2c_transfer_error(spec_, messages.front().address,
                                  messages.size() > 1 ? "combined transfer" : (messages.front().read ? "read" : "write"),
                                  injected_errno_);
    }
    const char* operation = messages.size() > 1 ? "combined transfer" : (messages.front().read ? "read" : "write");
    for (std::size_t m = 0; m < messages.size(); ++m) {
        auto& msg = messages[m];
        I2cLogEntry entry;
        entry.time = now_;
        entry.kind = msg.read ? I2cLogEntry::Kind::read : I2cLogEntry::Kind::write;
        entry.read_bit = msg.read;
        entry.address = msg.address;
        entry.repeated_start = m > 0;
        charge_bits(1 + 9);  // (repeated) START + address byte + ACK bit
        // Every device sees the address byte; the ones that ACK take part.
        std::vector<I2cDevice*> active;
        for (auto& d : devices_)
            if (d->on_address(msg.address, msg.read, now_)) active.push_back(d.get());
        entry.acked = !active.empty();
        if (active.empty()) {
            log_.push_back(std::move(entry));
            stop_all();
            return i2c_transfer_error(spec_, msg.address, operation, ENXIO);
        }
        for (std::size_t i = 0; i < msg.data.size(); ++i) {
            charge_bits(9);
            if (msg.read) {
                // Open-drain SDA: a 0 from any driver wins.
                std::uint8_t byte = 0xff;
                for (auto* d : active) byte &= d->on_read_byte(now_);
                msg.data[i] = byte;
                entry.data.push_back(byte);
            } else {
                bool ack = false;
                for (auto* d : active) ack = d->on_write_byte(msg.data[i], now_) || ack;
                entry.data.push_back(msg.data[i]);
                if (!ack) {
                    log_.push_back(std::move(entry));
                    stop_all();
                    return i2c_transfer_error(spec_, msg.address, operation, EREMOTEIO);
                }
            }
        }
        log_.push_back(std::move(entry));
    }
    stop_all();
    return {};
}

Status FakeI2cBus::quick(std::uint8_t address, bool read) {
    std::lock_guard lock(mutex_);
    if (!funcs_.smbus_quick)
        return Status(ErrorCode::unsupported,
                      "i2c " + spec_ + ": the adapter does not support SMBus quick commands "
                                       "(I2C_FUNC_SMBUS_QUICK), which TakkStrip select/deselect needs; use an "
                                       "adapter that does (most SoC I2C controllers and i2c-gpio do)");
    if (injected_count_ > 0) {
        --injected_count_;
        return i2c_transfer_error(spec_, address, read ? "quick read" : "quick write", injected_errno_);
    }
    I2cLogEntry entry;
    entry.time = now_;
    entry.kind = I2cLogEntry::Kind::quick;
    entry.read_bit = read;
    entry.address = address;
    charge_bits(1 + 9);
    bool ack = false;
    for (auto& d : devices_) ack = d->on_address(address, read, now_) || ack;
    entry.acked = ack;
    log_.push_back(std::move(entry));
    stop_all();
    if (!ack) return i2c_transfer_error(spec_, address, read ? "quick read" : "quick write", ENXIO);
    return {};
}

void FakeI2cBus::sleep_for(std::chrono::microseconds duration) {
    std::lock_guard lock(mutex_);
    now_ += static_cast<double>(duration.count()) * 1e-6;
}

void FakeI2cBus::attach(std::shared_ptr<I2cDevice> device) {
    std::lock_guard lock(mutex_);
    devices_.push_back(std::move(device));
}

void FakeI2cBus::detach(const std::shared_ptr<I2cDevice>& device) {
    std::lock_guard lock(mutex_);
    devices_.erase(std::remove(devices_.begin(), devices_.end(), device), devices_.end());
}

void FakeI2cBus::detach_all() {
    std::lock_guard lock(mutex_);
    devices_.clear();
}

double FakeI2cBus::now() const {
    std::lock_guard lock(mutex_);
    return now_;
}

void FakeI2cBus::set_clock_hz(double hz) {
    std::lock_guard lock(mutex_);
    if (hz > 0) clock_hz_ = hz;
}

void FakeI2cBus::set_functionality(I2cFunctionality f) {
    std::lock_guard lock(mutex_);
    funcs_ = f;
}

void FakeI2cBus::inject_errno(int err, int count) {
    std::lock_guard lock(mutex_);
    injected_errno_ = err;
    injected_count_ = count;
}

std::vector<I2cLogEntry> FakeI2cBus::log() const {
    std::lock_guard lock(mutex_);
    return log_;
}

void FakeI2cBus::clear_log() {
    std::lock_guard lock(mutex_);
    log_.clear();
}

void FakeI2cBus::reset() {
    std::lock_guard lock(mutex_);
    devices_.clear();
    log_.clear();
    injected_count_ = 0;
    injected_errno_ = 0;
    funcs_.raw = kDefaultFuncs;
    funcs_.combined_transfers = true;
    funcs_.smbus_quick = true;
    clock_hz_ = 400e3;
}

}  // namespace rollsense::hal
