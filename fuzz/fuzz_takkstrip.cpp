// TakkStrip reads (hal/i2c/src/takkstrip.cpp, mpl115a.cpp): a bus whose every
// ACK/NACK and every byte read comes from the input drives a probe of all
// strips, coefficient and ADC reads and the compensation; whatever the bus
// says, the results are errors or values in the chip's ranges.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "fuzz_support.hpp"
#include "rollsense/hal/takkstrip.hpp"

namespace hal = rollsense::hal;

namespace {

class InputBus final : public hal::I2cBus {
public:
    InputBus(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    const std::string& name() const override { return name_; }
    hal::I2cFunctionality functionality() const override {
        hal::I2cFunctionality f;
        f.combined_transfers = true;
        f.smbus_quick = true;
        return f;
    }
    rollsense::Status transfer(std::span<hal::I2cMessage> messages) override {
        if (nack()) return {rollsense::ErrorCode::io_error, "fuzz: NACK"};
        for (auto& m : messages)
            if (m.read)
                for (auto& b : m.data) b = byte();
        return {};
    }
    rollsense::Status quick(std::uint8_t, bool) override {
        if (nack()) return {rollsense::ErrorCode::io_error, "fuzz: NACK"};
        return {};
    }
    void sleep_for(std::chrono::microseconds) override {}

private:
    std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0xFF; }  // an idle bus reads high
    bool nack() { return (byte() & 0x0F) == 0x0F; }

    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
    std::string name_ = "fuzz";
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    auto bus = std::make_shared<InputBus>(data, size);
    hal::takkstrip::Host host(bus);
    auto report = hal::takkstrip::probe_strips(host, {0, 1, 2});
    if (report.ok())
        for (const auto& s : report->sensors) {
            if (!s.coefficients || !s.reading) continue;
            if (s.reading->padc > 1023 || s.reading->tadc > 1023)
                rollsense::fuzz::invariant_broken("an ADC reading outside 10 bits");
            const double p = hal::mpl115a::compensate(*s.coefficients, s.reading->padc, s.reading->tadc);
            if (!std::isfinite(p)) rollsense::fuzz::invariant_broken("compensated pressure not finite");
            (void)hal::mpl115a::pcomp_to_kpa(p);
        }
    // Direct reads of one slot as well, as the sensor plugin does each sample.
    const auto slot = hal::takkstrip::select_address(0, 0);
    (void)host.start_conversion_all();
    (void)host.read_coefficients(slot);
    (void)host.read_adc(slot);
    return 0;
}
