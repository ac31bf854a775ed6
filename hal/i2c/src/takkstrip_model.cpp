#include "rollsense/hal/takkstrip_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rollsense/hal/takkstrip.hpp"
#include "rollsense/random.hpp"

namespace rollsense::hal {
namespace {


std::int16_t to_word(double v) {
    return static_cast<std::int16_t>(std::clamp(std::lround(v), -32768L, 32767L));
}

}  // namespace

mpl115a::CoefficientWords plausible_coefficients(std::uint64_t seed) {
    // The SDK's splitmix64, so a seed gives the same chip on every platform.
    random::SplitMix64 rng(seed);
    auto u = [&] { return 2.0 * rng.uniform() - 1.0; };
    mpl115a::CoefficientWords w;
    w.a0 = to_word((2009.75 + 60.0 * u()) * 8.0);
    w.b1 = to_word((-2.37585 + 0.08 * u()) * 8192.0);
    w.b2 = to_word((-0.92047 + 0.04 * u()) * 16384.0);
    // 14 significant bits, then the two always-zero bits.
    w.c12 = static_cast<std::int16_t>(to_word((0.00079 + 0.00006 * u()) * 4194304.0) * 4);
    return w;
}

std::shared_ptr<TakkStripModel> make_takkstrip_model(TakkStripModelConfig config) {
    return std::make_shared<TakkStripModel>(config);
}

// ------------------------------------------------------------ Mpl115aChip --

Mpl115aChip::Mpl115aChip(mpl115a::CoefficientWords words, std::uint64_t noise_seed)
    : coefficients_(mpl115a::from_words(words)),
      coefficient_bytes_(mpl115a::encode_coefficients(words)),
      rng_(noise_seed) {
    // Power-on registers hold the result of a conversion at the initial conditions.
    const auto t = static_cast<std::uint16_t>(std::clamp(std::lround(mpl115a::kTadcAt25C), 0L, 1023L));
    adc_ = {padc_for(kpa_, t), t};
    pending_ = adc_;
}

void Mpl115aChip::set_pressure_kpa(double kpa) {
    std::lock_guard lock(mutex_);
    kpa_ = kpa;
    source_ = nullptr;
}

void Mpl115aChip::set_pressure_source(PressureSource source) {
    std::lock_guard lock(mutex_);
    source_ = std::move(source);
}

void Mpl115aChip::set_temperature_c(double celsius) {
    std::lock_guard lock(mutex_);
    celsius_ = celsius;
}

void Mpl115aChip::set_noise_counts(double sigma) {
    std::lock_guard lock(mutex_);
    noise_ = std::max(0.0, sigma);
}

void Mpl115aChip::set_conversion_time(double seconds) {
    std::lock_guard lock(mutex_);
    conversion_time_ = std::max(0.0, seconds);
}

void Mpl115aChip::set_fault(Mpl115aFault fault) {
    std::lock_guard lock(mutex_);
    fault_ = fault;
}

Mpl115aFault Mpl115aChip::fault() const {
    std::lock_guard lock(mutex_);
    return fault_;
}

int Mpl115aChip::conversions_started() const {
    std::lock_guard lock(mutex_);
    return conversions_;
}

int Mpl115aChip::early_reads() const {
    std::lock_guard lock(mutex_);
    return early_reads_;
}

mpl115a::AdcReading Mpl115aChip::last_result() const {
    std::lock_guard lock(mutex_);
    return converting_ ? pending_ : adc_;
}

double Mpl115aChip::gaussian() {
    // Box–Muller on the chip's own generator: reproducible for a given seed.
    const double u1 = std::max(rng_.uniform(), 1e-300);
    const double u2 = rng_.uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

std::uint16_t Mpl115aChip::padc_for(double kpa, std::uint16_t tadc) const {
    // Invert the datasheet compensation: the count this chip's coefficients
    // turn back into `kpa`.
    const auto& c = coefficients_;
    const double pcomp = (kpa - mpl115a::kMinKpa) * 1023.0 / (mpl115a::kMaxKpa - mpl115a::kMinKpa);
    const double padc = (pcomp - c.a0 - c.b2 * tadc) / (c.b1 + c.c12 * tadc);
    return static_cast<std::uint16_t>(std::clamp(std::lround(padc), 0L, 1023L));
}

void Mpl115aChip::finish_conversion_if_due(double time) {
    if (converting_ && time >= conversion_done_at_) {
        adc_ = pending_;
        converting_ = false;
    }
}

bool Mpl115aChip::on_address(bool read, double time) {
    std::lock_guard lock(mutex_);
    if (fault_ == Mpl115aFault::nack) return false;
    finish_conversion_if_due(time);
    expect_pointer_ = !read;
    expect_command_data_ = false;
    if (read && converting_ && pointer_ < 4) ++early_reads_;
    return true;
}

bool Mpl115aChip::on_write_byte(std::uint8_t value, double time) {
    std::lock_guard lock(mutex_);
    if (expect_pointer_) {
        pointer_ = value;
        expect_pointer_ = false;
        expect_command_data_ = value == mpl115a::kRegStartConversion;
        return true;
    }
    if (expect_command_data_) {
        // The data byte after 0x12 starts the conversion; its value is ignored.
        expect_command_data_ = false;
        ++conversions_;
        if (fault_ == Mpl115aFault::stuck) return true;  // the ADC no longer updates
        finish_conversion_if_due(time);
        double t_noise = noise_ > 0 ? noise_ * gaussian() : 0.0;
        const auto tadc = static_cast<std::uint16_t>(std::clamp(
            std::lround(mpl115a::kTadcAt25C + (celsius_ - 25.0) * mpl115a::kTadcPerDegC + t_noise), 0L, 1023L));
        const double kpa = source_ ? source_(time) : kpa_;
        auto padc = padc_for(kpa, tadc);
        if (noise_ > 0)
            padc = static_cast<std::uint16_t>(std::clamp(std::lround(padc + noise_ * gaussian()), 0L, 1023L));
        pending_ = {padc, tadc};
        converting_ = true;
        conversion_done_at_ = time + conversion_time_;
        return true;
    }
    return true;  // further bytes are accepted and ignored
}

std::uint8_t Mpl115aChip::on_read_byte(double time) {
    std::lock_guard lock(mutex_);
    finish_conversion_if_due(time);
    std::uint8_t value = 0x00;
    if (pointer_ < 4) {
        value = mpl115a::encode_adc(adc_)[pointer_];
    } else if (pointer_ < 12) {
        value = coefficient_bytes_[pointer_ - 4];
    }
    ++pointer_;  // auto-increment
    return value;
}

void Mpl115aChip::on_stop(double time) {
    std::lock_guard lock(mutex_);
    finish_conversion_if_due(time);
    expect_pointer_ = false;
    expect_command_data_ = false;
}

// --------------------------------------------------------- TakkStripModel --

TakkStripModel::TakkStripModel(TakkStripModelConfig config) : config_(config) {
    if (config_.strip < 0 || config_.strip >= takkstrip::kMaxStrips)
        throw std::invalid_argument("TakkStripModel: strip " + std::to_string(config_.strip) + " outside 0–11");
    if (config_.sensors < 1 || config_.sensors > takkstrip::kMaxSlots)
        throw std::invalid_argument("TakkStripModel: " + std::to_string(config_.sensors) + " sensors, must be 1–6");
    for (int slot = 0; slot < config_.sensors; ++slot) {
        const std::uint64_t chip_seed = config_.seed * 0x100000001b3ULL + static_cast<std::uint64_t>(config_.strip * 8 + slot);
        auto chip = std::make_unique<Mpl115aChip>(plausible_coefficients(chip_seed), chip_seed ^ 0x5eedULL);
        chip->set_conversion_time(config_.conversion_time);
        chip->set_noise_counts(config_.noise_counts);
        chip->set_pressure_kpa(config_.pressure_kpa);
        chips_.push_back(std::move(chip));
    }
    selected_.assign(chips_.size(), false);
    missing_.assign(chips_.size(), false);
}

Mpl115aChip& TakkStripModel::chip(int slot) {
    if (slot < 0 || slot >= sensor_count())
        throw std::out_of_range("TakkStripModel: no slot " + std::to_string(slot));
    return *chips_[static_cast<std::size_t>(slot)];
}

std::uint8_t TakkStripModel::select_address(int slot) const { return takkstrip::select_address(config_.strip, slot); }

void TakkStripModel::set_slot_missing(int slot, bool missing) {
    std::lock_guard lock(mutex_);
    if (slot < 0 || slot >= sensor_count()) throw std::out_of_range("TakkStripModel: no slot " + std::to_string(slot));
    missing_[static_cast<std::size_t>(slot)] = missing;
    if (missing) selected_[static_cast<std::size_t>(slot)] = false;
}

bool TakkStripModel::selected(int slot) const {
    std::lock_guard lock(mutex_);
    return slot >= 0 && slot < sensor_count() && selected_[static_cast<std::size_t>(slot)];
}

int TakkStripModel::contended_reads() const {
    std::lock_guard lock(mutex_);
    return contended_reads_;
}

bool TakkStripModel::on_address(std::uint8_t address, bool read, double time) {
    std::lock_guard lock(mutex_);
    talking_.clear();
    target_ = Target::none;
    const int first = config_.strip * 8;
    if (address == takkstrip::kAllStrips) {
        // Every strip's ATtiny answers the all-strips address.
        for (std::size_t i = 0; i < selected_.size(); ++i) selected_[i] = !read && !missing_[i];
        target_ = Target::attiny;
        return true;
    }
    if (address >= first && address < first + sensor_count()) {
        const auto slot = static_cast<std::size_t>(address - first);
        if (missing_[slot]) return false;
        if (read) {
            selected_[slot] = false;
        } else {
            // Selecting one chip releases the others on this strip (one RST high).
            std::fill(selected_.begin(), selected_.end(), false);
            selected_[slot] = true;
        }
        target_ = Target::attiny;
        return true;
    }
    if (address == mpl115a::kAddress) {
        for (std::size_t i = 0; i < chips_.size(); ++i)
            if (selected_[i] && chips_[i]->on_address(read, time)) talking_.push_back(static_cast<int>(i));
        if (talking_.empty()) return false;
        if (read && talking_.size() > 1) ++contended_reads_;
        target_ = Target::chips;
        return true;
    }
    return false;
}

bool TakkStripModel::on_write_byte(std::uint8_t value, double time) {
    std::lock_guard lock(mutex_);
    if (target_ == Target::attiny) return true;
    bool ack = false;
    for (int i : talking_) ack = chips_[static_cast<std::size_t>(i)]->on_write_byte(value, time) || ack;
    return ack;
}

std::uint8_t TakkStripModel::on_read_byte(double time) {
    std::lock_guard lock(mutex_);
    // The ATtiny's reply byte to a 1-byte deselect read is not documented; the
    // host ignores it, the model sends 0x00.
    if (target_ == Target::attiny) return 0x00;
    std::uint8_t byte = 0xff;
    for (int i : talking_) byte &= chips_[static_cast<std::size_t>(i)]->on_read_byte(time);
    return byte;
}

void TakkStripModel::on_stop(double time) {
    std::lock_guard lock(mutex_);
    for (auto& c : chips_) c->on_stop(time);
    talking_.clear();
    target_ = Target::none;
}

}  // namespace rollsense::hal
