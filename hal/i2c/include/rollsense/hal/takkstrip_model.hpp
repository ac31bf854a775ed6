// A device model of a TakkStrip for the fake I2C bus: the ATtiny's select /
// deselect behaviour on the address byte, and per-slot MPL115A2 register
// files with realistic coefficients, conversion timing and ADC values.
//
//   auto bus = rollsense::hal::FakeI2cBus::get("strip");
//   auto strip = std::make_shared<rollsense::hal::TakkStripModel>(TakkStripModelConfig{});
//   bus->attach(strip);
//   strip->chip(1).set_pressure_kpa(104.2);
//   strip->chip(2).set_pressure_source([](double t) { return 101.3 + 5 * std::sin(t); });
//
// What it enforces, like the hardware does:
//   - a chip talks at 0x60 only while selected (its RST high); several selected
//     chips drive the bus together (wired-AND on reads, see FakeI2cBus);
//   - a conversion started by 0x12 finishes conversion_time later on the bus's
//     clock; reading before that returns the previous result (and is counted,
//     so tests can prove the host waited);
//   - the pressure is sampled at the start of the conversion and turned into
//     the Padc that the chip's own coefficients compensate back to it.
// Faults: a slot the ATtiny does not acknowledge (missing sensor), a chip
// that NACKs at 0x60 (dead chip), a chip whose ADC stops converting (stuck).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "rollsense/hal/fake_i2c_bus.hpp"
#include "rollsense/hal/mpl115a.hpp"
#include "rollsense/random.hpp"

namespace rollsense::hal {

enum class Mpl115aFault {
    none,
    nack,   // the chip does not acknowledge its address (dead, or its RST line broken)
    stuck,  // the chip answers but its ADC registers never change again
};

// Pressure in kPa as a function of the bus clock (seconds).
using PressureSource = std::function<double(double time)>;

// One MPL115A2. Not an I2cDevice itself: the strip routes 0x60 traffic to the
// chips it has selected.
class Mpl115aChip {
public:
    Mpl115aChip(mpl115a::CoefficientWords words, std::uint64_t noise_seed);

    // ---- the physical world ----
    void set_pressure_kpa(double kpa);
    void set_pressure_source(PressureSource source);
    void set_temperature_c(double celsius);
    // Gaussian ADC noise in counts (0 = none; real chips show about ±1 count).
    void set_noise_counts(double sigma);
    void set_conversion_time(double seconds);
    void set_fault(Mpl115aFault fault);
    Mpl115aFault fault() const;

    // ---- what tests inspect ----
    const mpl115a::Coefficients& coefficients() const { return coefficients_; }
    int conversions_started() const;
    // Reads of the ADC registers while a conversion was still running.
    int early_reads() const;
    // The ADC values the last conversion produced.
    mpl115a::AdcReading last_result() const;

    // ---- bus side, called by TakkStripModel ----
    bool on_address(bool read, double time);
    bool on_write_byte(std::uint8_t value, double time);
    std::uint8_t on_read_byte(double time);
    void on_stop(double time);

private:
    void finish_conversion_if_due(double time);
    std::uint16_t padc_for(double kpa, std::uint16_t tadc) const;
    double gaussian();

    mutable std::mutex mutex_;
    mpl115a::Coefficients coefficients_;
    std::array<std::uint8_t, 8> coefficient_bytes_;
    PressureSource source_;
    double kpa_ = 101.325;
    double celsius_ = 25.0;
    double noise_ = 0.0;
    double conversion_time_ = 1.6e-3;
    Mpl115aFault fault_ = Mpl115aFault::none;
    random::SplitMix64 rng_;  // measurement noise

    // register pointer state of the current write message
    bool expect_pointer_ = false;
    bool expect_command_data_ = false;
    std::uint8_t pointer_ = 0;
    // conversion state
    bool converting_ = false;
    double conversion_done_at_ = 0.0;
    mpl115a::AdcReading pending_{};
    mpl115a::AdcReading adc_{};
    int conversions_ = 0;
    int early_reads_ = 0;
};

struct TakkStripModelConfig {
    int strip = 0;            // address jumpers: select addresses 8·strip + slot
    int sensors = 6;          // chips on the strip (TakkStrip 2: 6; v1 firmware: 5)
    std::uint64_t seed = 1;   // per-chip coefficients and noise derive from it
    double conversion_time = 1.6e-3;  // seconds (datasheet: 1.6 ms typical, 3 ms max)
    double noise_counts = 0.0;
    double pressure_kpa = 101.325;    // initial ambient pressure of every chip
};

class TakkStripModel final : public I2cDevice {
public:
    explicit TakkStripModel(TakkStripModelConfig config = {});

    int strip() const { return config_.strip; }
    int sensor_count() const { return static_cast<int>(chips_.size()); }
    Mpl115aChip& chip(int slot);
    std::uint8_t select_address(int slot) const;

    // The ATtiny does not acknowledge this slot (a missing or unpopulated chip).
    void set_slot_missing(int slot, bool missing);
    bool selected(int slot) const;
    // How often two or more chips were selected while 0x60 was read.
    int contended_reads() const;

    bool on_address(std::uint8_t address, bool read, double time) override;
    bool on_write_byte(std::uint8_t value, double time) override;
    std::uint8_t on_read_byte(double time) override;
    void on_stop(double time) override;

private:
    enum class Target { none, attiny, chips };

    TakkStripModelConfig config_;
    std::vector<std::unique_ptr<Mpl115aChip>> chips_;
    mutable std::mutex mutex_;
    std::vector<bool> selected_;
    std::vector<bool> missing_;
    std::vector<int> talking_;  // chips that ACKed 0x60 in the current message
    Target target_ = Target::none;
    int contended_reads_ = 0;
};

// Create a model whose shared_ptr control block lives in this library. Code
// that may be unloaded while the (process-wide) fake bus still holds the model
// — a plugin — must use this rather than std::make_shared, or the bus would
// later call a destructor in an unmapped library.
std::shared_ptr<TakkStripModel> make_takkstrip_model(TakkStripModelConfig config = {});

// Realistic coefficient words around the datasheet example (a0 ≈ 2009.75,
// b1 ≈ −2.376, b2 ≈ −0.920, c12 ≈ 0.00079), varied per chip by `seed`.
mpl115a::CoefficientWords plausible_coefficients(std::uint64_t seed);

}  // namespace rollsense::hal
