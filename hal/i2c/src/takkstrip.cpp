#include "rollsense/hal/takkstrip.hpp"

#include <array>

namespace rollsense::hal::takkstrip {
namespace {

// Keep the first failure; mention a second one (usually the clean-up deselect).
Status combine(Status first, const Status& second, const char* second_what) {
    if (first.ok()) return second;
    if (second.ok()) return first;
    return Status(first.code(), first.message() + "; then " + second_what + " failed too: " + second.message());
}

}  // namespace

std::uint8_t select_address(int strip, int slot) { return static_cast<std::uint8_t>(8 * strip + slot); }

std::string describe_select(std::uint8_t a) {
    return "strip " + std::to_string(a / 8) + " slot " + std::to_string(a % 8) + " (select " + format_i2c_address(a) +
           ")";
}

Status Host::select(std::uint8_t a) {
    auto s = bus_->quick_write(a);
    if (!s.ok()) return std::move(s).with_context("selecting " + describe_select(a));
    return s;
}

Status Host::deselect(std::uint8_t a) {
    auto s = bus_->quick_read(a);
    if (!s.ok()) return std::move(s).with_context("deselecting " + describe_select(a));
    return s;
}

Status Host::start_conversion_all() {
    if (auto s = select_all(); !s.ok()) return std::move(s).with_context("selecting all strips (0x06)");
    const std::uint8_t cmd[2] = {mpl115a::kRegStartConversion, 0x00};
    Status convert = bus_->write(mpl115a::kAddress, cmd);
    if (!convert.ok()) convert = std::move(convert).with_context("starting the conversion (0x12 to 0x60)");
    Status release = deselect_all();
    if (!release.ok()) release = std::move(release).with_context("deselecting all strips (0x06)");
    return combine(std::move(convert), release, "deselect all");
}

template <std::size_t N>
Status Host::read_registers(std::uint8_t a, std::uint8_t reg, std::array<std::uint8_t, N>& out) {
    if (auto s = select(a); !s.ok()) {
        // A failed select may still have half-selected something; release it.
        (void)bus_->quick_read(a);
        return s;
    }
    const std::uint8_t pointer[1] = {reg};
    Status rd = bus_->write_read(mpl115a::kAddress, pointer, out);
    if (!rd.ok()) rd = std::move(rd).with_context(describe_select(a) + ": reading registers from 0x60");
    return combine(std::move(rd), deselect(a), "deselect");
}

Result<mpl115a::Coefficients> Host::read_coefficients(std::uint8_t a) {
    std::array<std::uint8_t, 8> raw{};
    if (auto s = read_registers(a, mpl115a::kRegCoefficients, raw); !s.ok()) return s;
    auto c = mpl115a::decode_coefficients(raw);
    if (!c.ok()) return Status(c.error()).with_context(describe_select(a));
    return c;
}

Result<mpl115a::AdcReading> Host::read_adc(std::uint8_t a) {
    std::array<std::uint8_t, 4> raw{};
    if (auto s = read_registers(a, mpl115a::kRegPadc, raw); !s.ok()) return s;
    auto r = mpl115a::decode_adc(raw);
    if (!r.ok()) return Status(r.error()).with_context(describe_select(a));
    return r;
}

Status Host::probe(std::uint8_t a) {
    if (auto s = select(a); !s.ok()) return s;
    Status chip = bus_->quick_write(mpl115a::kAddress);
    if (!chip.ok()) chip = std::move(chip).with_context(describe_select(a) + ": no MPL115A at 0x60 while selected");
    return combine(std::move(chip), deselect(a), "deselect");
}

Result<ProbeReport> probe_strips(Host& host, const std::vector<int>& strips) {
    auto funcs = host.bus().functionality();
    if (!funcs.smbus_quick || !funcs.combined_transfers)
        return Error{ErrorCode::unsupported,
                     "i2c " + host.bus().name() +
                         ": the adapter lacks SMBus quick commands or combined I2C transfers; a TakkStrip needs both"};
    ProbeReport report;
    // Start from a known state: nobody selected. Its ACK also tells whether any
    // strip is there at all.
    report.all_strips_address_acked = host.deselect_all().ok();
    for (int strip : strips) {
        if (strip < 0 || strip >= kMaxStrips)
            return Error{ErrorCode::invalid_argument,
                         "strip " + std::to_string(strip) + " out of range: strips are 0–" + std::to_string(kMaxStrips - 1)};
        for (int slot = 0; slot < kMaxSlots; ++slot) {
            const auto a = select_address(strip, slot);
            if (a == kAllStrips) continue;  // strip 0 slot 6 would be the all-strips address
            auto ack = host.bus().quick_write(a);
            if (!ack.ok()) {
                if (ack.code() == ErrorCode::hardware_fault) continue;  // NACK: no such slot
                return ack;  // the bus itself is broken
            }
            (void)host.bus().quick_read(a);
            ProbedSensor p;
            p.strip = strip;
            p.slot = slot;
            p.select_address = a;
            p.chip = host.probe(a);
            if (p.chip.ok()) {
                auto c = host.read_coefficients(a);
                if (c.ok()) p.coefficients = c.value();
                p.coefficients_status = c.status();
            }
            report.sensors.push_back(std::move(p));
        }
    }
    // One conversion for everyone found, then read each: a quick sanity check
    // of the whole sample cycle.
    bool any = false;
    for (auto& p : report.sensors) any = any || p.coefficients.has_value();
    if (any) {
        Status conv = host.start_conversion_all();
        host.bus().sleep_for(mpl115a::kConversionTimeMax);
        for (auto& p : report.sensors) {
            if (!p.coefficients) continue;
            if (!conv.ok()) {
                p.reading_status = conv;
                continue;
            }
            auto r = host.read_adc(p.select_address);
            if (r.ok()) p.reading = r.value();
            p.reading_status = r.status();
        }
    }
    return report;
}

}  // namespace rollsense::hal::takkstrip
