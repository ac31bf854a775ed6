// Host side of the TakkStrip protocol: many MPL115A2 on one bus, all at 0x60,
// behind a per-strip ATtiny that drives each chip's RST line.
//
// Facts (TakkStrip v1 firmware; hardware.md §2 — unverified for TakkStrip 2):
//   select address = 8·strip + slot (7-bit). A quick write to it selects that
//   chip, a read (quick read or 1-byte read) deselects it. 0x06 addresses every
//   strip: write = select all, read = deselect all. An un-jumpered strip is
//   strip 0 (0x00–0x05; 0x00 is also the general-call address).
//   Sample cycle: select all → write 0x12,0x00 to 0x60 (every chip converts at
//   once) → deselect all → wait ≥ 3 ms → per chip: select, write pointer 0x00 +
//   repeated START + read 4 bytes from 0x60, deselect.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rollsense/hal/i2c.hpp"
#include "rollsense/hal/mpl115a.hpp"

namespace rollsense::hal::takkstrip {

inline constexpr std::uint8_t kAllStrips = 0x06;
// Strip s uses 8s..8s+5; strip 12 would reach 0x60, the barometers' own address.
inline constexpr int kMaxStrips = 12;
// v1 firmware: slots 0–4; a TakkStrip 2 carries six chips (slot 5, unverified).
inline constexpr int kMaxSlots = 6;

// 8·strip + slot; strip in [0, 12), slot in [0, 6).
std::uint8_t select_address(int strip, int slot);
// "strip 1 slot 2 (select 0x0a)"
std::string describe_select(std::uint8_t select_address);

class Host {
public:
    explicit Host(std::shared_ptr<I2cBus> bus) : bus_(std::move(bus)) {}
    I2cBus& bus() { return *bus_; }

    Status select(std::uint8_t select_address);    // quick write
    Status deselect(std::uint8_t select_address);  // quick read
    Status select_all() { return bus_->quick_write(kAllStrips); }
    Status deselect_all() { return bus_->quick_read(kAllStrips); }

    // select all → start conversion → deselect all. Deselects even when the
    // conversion command fails, so no chip is left driving the bus.
    Status start_conversion_all();
    // Select one chip, read (pointer, repeated START, n bytes), deselect it.
    Result<mpl115a::Coefficients> read_coefficients(std::uint8_t select_address);
    Result<mpl115a::AdcReading> read_adc(std::uint8_t select_address);
    // Does a chip answer at 0x60 while this one is selected? (quick write to
    // the slot, quick write to 0x60, deselect.)
    Status probe(std::uint8_t select_address);

private:
    template <std::size_t N>
    Status read_registers(std::uint8_t select_address, std::uint8_t reg, std::array<std::uint8_t, N>& out);

    std::shared_ptr<I2cBus> bus_;
};

// What `rollsense probe i2c` reports for one slot that ACKed its select address.
struct ProbedSensor {
    int strip = 0;
    int slot = 0;
    std::uint8_t select_address = 0;
    Status chip;  // does the MPL115A answer at 0x60 while selected
    std::optional<mpl115a::Coefficients> coefficients;
    Status coefficients_status;
    std::optional<mpl115a::AdcReading> reading;  // one conversion, if it worked
    Status reading_status;
};

struct ProbeReport {
    bool all_strips_address_acked = false;  // 0x06
    std::vector<ProbedSensor> sensors;      // slots that ACKed, in address order
};

// Discovery: for each strip and slot, quick-write the select address (an ACK
// means the slot exists), probe 0x60, read coefficients, convert once and
// read, deselect. Only a bus-level failure (unsupported adapter) is an error.
Result<ProbeReport> probe_strips(Host& host, const std::vector<int>& strips);

}  // namespace rollsense::hal::takkstrip
