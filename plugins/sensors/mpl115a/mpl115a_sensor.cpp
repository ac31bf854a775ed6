#include "mpl115a_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "rollsense/hal/fake_i2c_bus.hpp"
#include "rollsense/hal/takkstrip_model.hpp"
#include "rollsense/log.hpp"

namespace rollsense::plugins {

namespace ms = hal::mpl115a;
namespace ts = hal::takkstrip;

ParamSchema mpl115a_schema() {
    return {
        param_string("bus", std::string("/dev/i2c-1"),
                     "I2C bus: /dev/i2c-N, N, or fake:<name> (an in-process bus with a modelled strip)"),
        param_int("strip", 0, "TakkStrip address jumpers: sensor select address = 8·strip + slot", 0,
                  ts::kMaxStrips - 1),
        param_int_list("sensors", std::vector<std::int64_t>{0, 1, 2},
                       "active slots on that strip, in channel order (the paper: 3 adjacent of 12)", 0,
                       ts::kMaxSlots - 1),
        param_int_list("select_addresses", std::vector<std::int64_t>{},
                       "explicit 7-bit select addresses in channel order, for sensors on several strips "
                       "(e.g. [5, 8, 9]); overrides strip/sensors when non-empty",
                       0, 0x5f),
        param_string_list("channel_names", std::vector<std::string>{},
                          "channel names in order; empty = ch1, ch2, ..."),
        param_number("scale", 0.0625,
                     "output = (kPa − baseline kPa) · scale; 1/16 gives the paper's unitless reading (≈16 kPa/unit)",
                     1e-9, 1e9, "1/kPa"),
        param_number("conversion_time_ms", 3.0, "wait between starting a conversion and reading (datasheet max 3 ms)",
                     3.0, 100.0, "ms"),
        param_int("baseline_samples", 4, "conversions averaged into each channel's baseline when a recording starts",
                  1, 100),
        param_int("stuck_samples", 100,
                  "mark a sensor invalid after this many identical raw readings in a row (ADC stopped); 0 = off", 0,
                  100000),
        param_int("retries", 1, "extra attempts at a failed sensor read within one sample", 0, 5),
        param_int("fault_after", 31,
                  "end the run (hardware fault) when one channel has had no valid reading for this many samples in "
                  "a row (NACK, bus error, stuck ADC; 31 ≈ 1 s at 31.1 Hz); 0 = only mark the samples invalid",
                  0, 100000),
        param_string_list("inject", std::vector<std::string>{},
                          "faults to inject into the modelled strip (simulate = true only), each "
                          "'CHANNEL:KIND:AFTER_S' (run-clock seconds); KIND nack (the chip stops answering) or "
                          "stuck (its ADC stops converting: the same raw words forever)"),
        param_bool("raw_channels", false, "also output <name>_kpa (compensated kPa) and <name>_tadc (raw temperature count)"),
        param_bool("simulate", false,
                   "with a fake: bus on which no strip answers, attach a modelled TakkStrip at ambient pressure "
                   "(for trying a profile without hardware)"),
    };
}

namespace {

// "ch2:nack:1.5" → channel index, fault, time; names the entry when it is not one.
Status parse_injection(const std::string& spec, const std::vector<std::string>& channels, std::size_t& channel,
                       hal::Mpl115aFault& fault, double& after) {
    const auto a = spec.find(':'), b = spec.rfind(':');
    const std::string where = "inject '" + spec + "'";
    if (a == std::string::npos || a == b)
        return {ErrorCode::invalid_argument, where + ": expected CHANNEL:KIND:AFTER_S, e.g. ch2:nack:1.5"};
    const std::string name = spec.substr(0, a), kind = spec.substr(a + 1, b - a - 1), time = spec.substr(b + 1);
    const auto it = std::find(channels.begin(), channels.end(), name);
    if (it == channels.end()) return {ErrorCode::invalid_argument, where + ": no channel '" + name + "'"};
    channel = static_cast<std::size_t>(it - channels.begin());
    if (kind != "nack" && kind != "stuck")
        return {ErrorCode::invalid_argument, where + ": unknown kind '" + kind + "' (the strip model knows nack and stuck)"};
    fault = kind == "nack" ? hal::Mpl115aFault::nack : hal::Mpl115aFault::stuck;
    char* end = nullptr;
    after = std::strtod(time.c_str(), &end);
    if (time.empty() || *end != '\0' || !std::isfinite(after) || after < 0)
        return {ErrorCode::invalid_argument, where + ": AFTER_S must be a number of seconds >= 0"};
    return {};
}

std::string join_reasons(const std::vector<std::string>& reasons) {
    std::string s;
    for (const auto& r : reasons) {
        if (!s.empty()) s += "; ";
        s += r;
    }
    return s;
}

}  // namespace

Status Mpl115aSensor::on_configure(const ParamSet& params, const PluginContext& context) {
    (void)context;
    std::lock_guard lock(mutex_);
    release();
    scale_ = params.get_number("scale");
    conversion_time_ = std::chrono::microseconds(std::llround(params.get_number("conversion_time_ms") * 1000.0));
    baseline_samples_ = static_cast<int>(params.get_int("baseline_samples"));
    stuck_samples_ = static_cast<int>(params.get_int("stuck_samples"));
    retries_ = static_cast<int>(params.get_int("retries"));
    fault_after_ = static_cast<int>(params.get_int("fault_after"));
    raw_channels_ = params.get_bool("raw_channels");

    // Which sensors, in channel order.
    std::vector<std::uint8_t> selects;
    for (auto a : params.get_int_list("select_addresses")) {
        if (a == ts::kAllStrips)
            return Status(ErrorCode::invalid_argument,
                          "select_addresses: 0x06 is the all-strips address, not a sensor (strip 0 has slots 0x00–0x05)");
        if (a % 8 >= ts::kMaxSlots)
            return Status(ErrorCode::invalid_argument, "select_addresses: " + hal::format_i2c_address(static_cast<std::uint8_t>(a)) +
                                                           " is slot " + std::to_string(a % 8) + "; slots are 0–5");
        selects.push_back(static_cast<std::uint8_t>(a));
    }
    if (selects.empty()) {
        const int strip = static_cast<int>(params.get_int("strip"));
        for (auto slot : params.get_int_list("sensors")) selects.push_back(ts::select_address(strip, static_cast<int>(slot)));
    }
    if (selects.empty()) return Status(ErrorCode::invalid_argument, "no sensors configured: 'sensors' is empty");
    if (std::set<std::uint8_t>(selects.begin(), selects.end()).size() != selects.size())
        return Status(ErrorCode::invalid_argument, "the same sensor is listed twice in 'sensors'/'select_addresses'");

    auto names = params.get_string_list("channel_names");
    if (!names.empty() && names.size() != selects.size())
        return Status(ErrorCode::invalid_argument, "channel_names has " + std::to_string(names.size()) +
                                                       " names for " + std::to_string(selects.size()) + " sensors");
    for (std::size_t i = 0; i < selects.size(); ++i) {
        Channel ch;
        ch.select = selects[i];
        ch.name = names.empty() ? "ch" + std::to_string(i + 1) : names[i];
        if (ch.name.empty() || ch.name.find_first_of(", \"\n") != std::string::npos)
            return Status(ErrorCode::invalid_argument, "channel name '" + ch.name +
                                                           "' is not usable as a CSV column (no commas, spaces, quotes)");
        channels_.push_back(ch);
    }

    // The bus.
    const std::string& spec = params.get_string("bus");
    auto bus = hal::open_i2c_bus(spec);
    if (!bus.ok()) {
        auto st = Status(bus.error()).with_context("bus '" + spec + "'");
        if (st.code() != ErrorCode::not_found) return st;
        return {st.code(), st.message() + "; without hardware, a modelled strip: bus = \"fake:strip\", simulate = true"};
    }
    bus_ = bus.value();
    const auto funcs = bus_->functionality();
    if (!funcs.smbus_quick || !funcs.combined_transfers)
        return Status(ErrorCode::unsupported,
                      "i2c " + bus_->name() + ": a TakkStrip needs SMBus quick commands (select/deselect) and "
                                              "combined I2C transfers; this adapter lacks " +
                          std::string(!funcs.smbus_quick ? "quick commands" : "combined transfers"));
    host_ = std::make_unique<ts::Host>(bus_);

    // Start from a known state; the ACK also proves a strip is there.
    Status all = host_->deselect_all();
    if (!all.ok() && params.get_bool("simulate")) {
        auto fake = std::dynamic_pointer_cast<hal::FakeI2cBus>(bus_);
        if (!fake)
            return Status(ErrorCode::invalid_argument, "simulate = true needs a fake: bus, not " + bus_->name());
        std::set<int> strips;
        for (const auto& ch : channels_) strips.insert(ch.select / 8);
        for (int strip : strips) {
            hal::TakkStripModelConfig cfg;
            cfg.strip = strip;
            cfg.noise_counts = 0.5;
            models_.push_back(hal::make_takkstrip_model(cfg));  // not make_shared: see its header
            fake->attach(models_.back());
        }
        log_info("mpl115a", "attached a modelled TakkStrip to " + bus_->name() + " (simulate = true)");
        all = host_->deselect_all();
    }
    if (!all.ok())
        return Status(all.code(), "no TakkStrip answers the all-strips address 0x06 on " + bus_->name() +
                                      " — check power and wiring, then run 'rollsense probe i2c " + spec +
                                      "' (" + all.message() + ")");

    for (auto& ch : channels_) {
        const std::string who = "channel " + ch.name + ", " + ts::describe_select(ch.select);
        if (auto s = host_->probe(ch.select); !s.ok())
            return std::move(s).with_context(who + " (see 'rollsense probe i2c " + spec + "')");
        auto c = host_->read_coefficients(ch.select);
        if (!c.ok()) return Status(c.error()).with_context(who + ": reading coefficients");
        ch.coefficients = c.value();
        log_debug("mpl115a", who + ": " + ms::describe(ch.coefficients));
    }

    std::vector<std::string> names_in_order;
    for (const auto& ch : channels_) names_in_order.push_back(ch.name);
    for (const auto& text : params.get_string_list("inject")) {
        Injection inj;
        if (auto st = parse_injection(text, names_in_order, inj.channel, inj.fault, inj.after); !st.ok()) return st;
        if (!modelled_chip(channels_[inj.channel].select))
            return {ErrorCode::invalid_argument,
                    "inject '" + text + "': faults go into the modelled strip, which this sensor did not attach; use "
                    "bus = 'fake:<name>' with simulate = true"};
        injections_.push_back(inj);
    }

    channel_info_.clear();
    for (const auto& ch : channels_)
        channel_info_.push_back({ch.name, "1",
                                 "baseline-subtracted pressure × scale, " + ts::describe_select(ch.select)});
    if (raw_channels_) {
        for (const auto& ch : channels_)
            channel_info_.push_back({ch.name + "_kpa", "kPa", "compensated pressure, " + ts::describe_select(ch.select)});
        for (const auto& ch : channels_)
            channel_info_.push_back({ch.name + "_tadc", "count",
                                     "raw temperature ADC (uncalibrated, about −5.35 counts/°C; use relatively)"});
    }
    return {};
}

hal::Mpl115aChip* Mpl115aSensor::modelled_chip(std::uint8_t select) {
    for (auto& m : models_)
        if (m->strip() == select / 8 && select % 8 < m->sensor_count()) return &m->chip(select % 8);
    return nullptr;
}

void Mpl115aSensor::apply_due_injections(double time) {
    for (auto& inj : injections_) {
        if (inj.applied || time < inj.after) continue;
        inj.applied = true;
        modelled_chip(channels_[inj.channel].select)->set_fault(inj.fault);
        log_info("mpl115a", "injected fault: channel " + channels_[inj.channel].name + " now " +
                                (inj.fault == hal::Mpl115aFault::nack ? "NACKs" : "has a stuck ADC") +
                                " (inject, t = " + std::to_string(time) + " s)");
    }
}

void Mpl115aSensor::release() {
    if (host_) (void)host_->deselect_all();
    // The strips this sensor attached leave the process-wide fake bus with it:
    // the next configure starts from a fresh, healthy model.
    if (auto fake = std::dynamic_pointer_cast<hal::FakeI2cBus>(bus_))
        for (auto& m : models_) fake->detach(m);
    models_.clear();
    injections_.clear();
    host_.reset();
    bus_.reset();
    channels_.clear();
    channel_info_.clear();
}

Status Mpl115aSensor::on_activate() {
    std::lock_guard lock(mutex_);
    if (!host_) return Status(ErrorCode::state_error, "activate before configure");
    for (auto& ch : channels_) {
        ch.has_baseline = false;
        ch.repeats = 0;
        ch.failed_samples = 0;
    }
    return {};
}

Status Mpl115aSensor::on_deactivate() {
    std::lock_guard lock(mutex_);
    // Leave no chip selected: a selected chip would answer someone else's 0x60 traffic.
    if (host_) (void)host_->deselect_all();
    return {};
}

Status Mpl115aSensor::on_cleanup() {
    std::lock_guard lock(mutex_);
    release();
    return {};
}

Status Mpl115aSensor::on_recover() {
    std::lock_guard lock(mutex_);
    release();
    return {};
}

std::vector<ChannelInfo> Mpl115aSensor::channels() const {
    std::lock_guard lock(mutex_);
    return channel_info_;
}

std::vector<Mpl115aSensor::SensorSample> Mpl115aSensor::sample_all() {
    std::vector<SensorSample> out(channels_.size());
    Status conv;
    for (int attempt = 0; attempt <= retries_; ++attempt) {
        conv = host_->start_conversion_all();
        if (conv.ok()) break;
    }
    if (!conv.ok()) {
        for (auto& s : out) s.reason = "starting the conversion: " + conv.message();
        return out;
    }
    bus_->sleep_for(conversion_time_);
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        auto& ch = channels_[i];
        Result<ms::AdcReading> r = Error{ErrorCode::io_error, "not read"};
        for (int attempt = 0; attempt <= retries_; ++attempt) {
            // The result stays in the chip's registers, so a retry re-reads the same conversion.
            r = host_->read_adc(ch.select);
            if (r.ok()) break;
        }
        if (!r.ok()) {
            out[i].reason = ch.name + ": " + r.error().message;
            continue;
        }
        out[i].ok = true;
        out[i].adc = r.value();
        out[i].kpa = ms::pressure_kpa(ch.coefficients, r.value());
    }
    return out;
}

Status Mpl115aSensor::take_baseline() {
    std::vector<double> sum(channels_.size(), 0.0);
    std::vector<int> good(channels_.size(), 0);
    std::vector<std::string> last_reason(channels_.size());
    // Allow a few extra cycles for transient failures before giving up.
    for (int cycle = 0; cycle < baseline_samples_ * 3; ++cycle) {
        bool done = true;
        for (std::size_t i = 0; i < channels_.size(); ++i) done = done && good[i] >= baseline_samples_;
        if (done) break;
        auto samples = sample_all();
        for (std::size_t i = 0; i < channels_.size(); ++i) {
            if (samples[i].ok && good[i] < baseline_samples_) {
                sum[i] += samples[i].kpa;
                ++good[i];
            } else if (!samples[i].ok) {
                last_reason[i] = samples[i].reason;
            }
        }
    }
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        if (good[i] == 0)
            return Status(ErrorCode::hardware_fault,
                          "no baseline for channel " + channels_[i].name + ": every read failed (" + last_reason[i] + ")");
        channels_[i].baseline_kpa = sum[i] / good[i];
        channels_[i].has_baseline = true;
        // The stuck count is not reset: a chip that stopped converting stays
        // stopped across recordings, and a roll may be shorter than stuck_samples.
    }
    return {};
}

Status Mpl115aSensor::start_recording(const SampleInput& input) {
    std::lock_guard lock(mutex_);
    if (!host_) return Status(ErrorCode::state_error, "start_recording before configure");
    apply_due_injections(input.time);
    return take_baseline();
}

Status Mpl115aSensor::read(const SampleInput& input, Frame& out) {
    std::lock_guard lock(mutex_);
    if (!host_) return Status(ErrorCode::state_error, "read before configure");
    apply_due_injections(input.time);
    // Reading outside a recording still gives meaningful values: baseline now.
    bool need_baseline = false;
    for (const auto& ch : channels_) need_baseline = need_baseline || !ch.has_baseline;
    if (need_baseline)
        if (auto s = take_baseline(); !s.ok()) {
            out.values.assign(channel_info_.size(), std::nan(""));
            out.valid = false;
            out.reason = s.message();
            return check_failing_channels(out);
        }

    const auto samples = sample_all();
    const std::size_t n = channels_.size();
    out.values.assign(channel_info_.size(), std::nan(""));
    std::vector<std::string> reasons;
    for (std::size_t i = 0; i < n; ++i) {
        auto& ch = channels_[i];
        const auto& s = samples[i];
        if (!s.ok) {
            reasons.push_back(s.reason);
            continue;
        }
        // A chip whose ADC stopped converting repeats its last words forever;
        // real readings carry at least a count of noise.
        if (s.adc.padc == ch.last.padc && s.adc.tadc == ch.last.tadc) {
            ++ch.repeats;
        } else {
            ch.repeats = 0;
            ch.last = s.adc;
        }
        if (stuck_samples_ > 0 && ch.repeats >= stuck_samples_) {
            reasons.push_back(ch.name + ": ADC stuck — the same raw reading (Padc " + std::to_string(s.adc.padc) +
                              ", Tadc " + std::to_string(s.adc.tadc) + ") " + std::to_string(ch.repeats + 1) +
                              " times in a row; the chip has stopped converting (power-cycle the strip)");
            continue;
        }
        out.values[i] = (s.kpa - ch.baseline_kpa) * scale_;
        if (raw_channels_) {
            out.values[n + i] = s.kpa;
            out.values[2 * n + i] = s.adc.tadc;
        }
    }
    out.valid = reasons.empty();
    out.reason = join_reasons(reasons);
    return check_failing_channels(out);
}

// A channel with no valid reading for fault_after samples in a row is not a
// glitch but a dead or stuck chip: the run ends with a hardware fault naming
// it (the kernel then makes the hand safe), rather than recording trials of NaN.
Status Mpl115aSensor::check_failing_channels(const Frame& out) {
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        auto& ch = channels_[i];
        ch.failed_samples = std::isnan(out.values[i]) ? ch.failed_samples + 1 : 0;
        if (fault_after_ > 0 && ch.failed_samples >= fault_after_)
            return {ErrorCode::hardware_fault,
                    "channel " + ch.name + ", " + ts::describe_select(ch.select) + ": no valid reading for " +
                        std::to_string(ch.failed_samples) + " samples in a row (" + out.reason +
                        "); check the strip's wiring and power, then 'rollsense probe i2c " + bus_->name() + "'"};
    }
    return {};
}

Result<ValueMap> Mpl115aSensor::invoke(const std::string& verb, const ValueMap& args) {
    (void)args;
    std::lock_guard lock(mutex_);
    if (verb == "coefficients") {
        ValueMap m;
        for (const auto& ch : channels_) {
            m[ch.name + ".select"] = static_cast<std::int64_t>(ch.select);
            m[ch.name + ".a0"] = ch.coefficients.a0;
            m[ch.name + ".b1"] = ch.coefficients.b1;
            m[ch.name + ".b2"] = ch.coefficients.b2;
            m[ch.name + ".c12"] = ch.coefficients.c12;
        }
        return m;
    }
    if (verb == "baseline") {
        ValueMap m;
        for (const auto& ch : channels_)
            if (ch.has_baseline) m[ch.name] = ch.baseline_kpa;
        return m;
    }
    if (verb == "rebaseline") {
        if (!host_) return Error{ErrorCode::state_error, "rebaseline before configure"};
        if (auto s = take_baseline(); !s.ok()) return s;
        ValueMap m;
        for (const auto& ch : channels_) m[ch.name] = ch.baseline_kpa;
        return m;
    }
    return Error{ErrorCode::unsupported,
                 "no operation '" + verb + "' (mpl115a knows: coefficients, baseline, rebaseline)"};
}

}  // namespace rollsense::plugins
