// The libgpiod 1.6 (v1 API) backend: the GPIO character device /dev/gpiochipN.
//
// Inputs are requested for both-edge events, so one request gives the level
// (gpiod_line_get_value) and the edges (gpiod_line_event_wait/_read); the
// kernel applies ACTIVE_LOW to both. Every libgpiod call returns −1/NULL and
// sets errno on failure; messages name the chip, the line and the way out.
#include <gpiod.h>

#include <cerrno>
#include <cstring>

#include "rollsense/hal/gpio.hpp"

namespace rollsense::hal {
namespace {

std::string where(const GpioLineConfig& cfg) { return "GPIO " + cfg.chip + " line " + std::to_string(cfg.line); }

struct ChipCloser {
    void operator()(gpiod_chip* c) const noexcept {
        if (c) gpiod_chip_close(c);
    }
};
using ChipPtr = std::unique_ptr<gpiod_chip, ChipCloser>;

Result<ChipPtr> open_chip(const GpioLineConfig& cfg) {
    if (cfg.chip.empty())
        return Error{ErrorCode::invalid_argument, "GPIO chip not given: use e.g. \"gpiochip0\" or \"fake:<name>\""};
    errno = 0;
    gpiod_chip* chip = cfg.chip[0] == '/' ? gpiod_chip_open(cfg.chip.c_str()) : gpiod_chip_open_by_name(cfg.chip.c_str());
    if (!chip) {
        const int err = errno;
        if (err == ENODEV || err == ENOTTY)
            return Error{ErrorCode::invalid_argument,
                         "'" + cfg.chip + "' is not a GPIO character device: use a chip listed by 'gpiodetect'"};
        if (err == ENOENT)
            return Error{ErrorCode::not_found,
                         "GPIO chip '" + cfg.chip + "' not found (no such device node under /dev): list the chips "
                         "with 'gpiodetect' (a fake chip such as \"fake:estop\" stands in only without hardware, in tests "
                         "and the simulation: it never trips, so never on a real hand)"};
        if (err == EACCES || err == EPERM)
            return Error{ErrorCode::io_error, "permission denied opening GPIO chip '" + cfg.chip +
                                                  "': add your user to the 'gpio' group or install a udev rule"};
        return Error{ErrorCode::io_error, "cannot open GPIO chip '" + cfg.chip + "': " + std::strerror(err)};
    }
    return ChipPtr(chip);
}

Result<gpiod_line*> get_line(gpiod_chip* chip, const GpioLineConfig& cfg) {
    const unsigned n = gpiod_chip_num_lines(chip);
    if (cfg.line >= n)
        return Error{ErrorCode::not_found, where(cfg) + ": the chip has lines 0–" + std::to_string(n ? n - 1 : 0)};
    gpiod_line* line = gpiod_chip_get_line(chip, cfg.line);
    if (!line) return Error{ErrorCode::io_error, where(cfg) + ": " + std::strerror(errno)};
    return line;
}

Error request_error(const GpioLineConfig& cfg, int err) {
    if (err == EBUSY)
        return {ErrorCode::io_error, where(cfg) + " is busy: another consumer holds it (see 'gpioinfo')"};
    return {ErrorCode::io_error, where(cfg) + ": request failed: " + std::strerror(err)};
}

int flags(const GpioLineConfig& cfg) { return cfg.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0; }

class GpiodInput final : public GpioInput {
public:
    GpiodInput(ChipPtr chip, gpiod_line* line, GpioLineConfig cfg)
        : chip_(std::move(chip)), line_(line), cfg_(std::move(cfg)) {}
    ~GpiodInput() override { gpiod_line_release(line_); }
    GpiodInput(const GpiodInput&) = delete;
    GpiodInput& operator=(const GpiodInput&) = delete;

    Result<bool> is_active() override {
        const int v = gpiod_line_get_value(line_);
        if (v < 0) return Error{ErrorCode::io_error, where(cfg_) + ": reading the level: " + std::strerror(errno)};
        return v == 1;
    }

    Result<bool> wait_for_edge(std::chrono::milliseconds timeout) override {
        const auto ms = timeout.count() < 0 ? 0 : timeout.count();
        timespec ts{static_cast<time_t>(ms / 1000), static_cast<long>((ms % 1000) * 1000000L)};
        const int r = gpiod_line_event_wait(line_, &ts);
        if (r < 0) return Error{ErrorCode::io_error, where(cfg_) + ": waiting for an edge: " + std::strerror(errno)};
        if (r == 0) return false;
        gpiod_line_event event{};
        if (gpiod_line_event_read(line_, &event) < 0)
            return Error{ErrorCode::io_error, where(cfg_) + ": reading the edge event: " + std::strerror(errno)};
        return true;
    }

private:
    ChipPtr chip_;
    gpiod_line* line_;
    GpioLineConfig cfg_;
};

class GpiodOutput final : public GpioOutput {
public:
    GpiodOutput(ChipPtr chip, gpiod_line* line, GpioLineConfig cfg)
        : chip_(std::move(chip)), line_(line), cfg_(std::move(cfg)) {}
    ~GpiodOutput() override { gpiod_line_release(line_); }
    GpiodOutput(const GpiodOutput&) = delete;
    GpiodOutput& operator=(const GpiodOutput&) = delete;

    Status set_active(bool active) override {
        if (gpiod_line_set_value(line_, active ? 1 : 0) < 0)
            return Status(ErrorCode::io_error, where(cfg_) + ": setting the level: " + std::strerror(errno));
        return {};
    }

private:
    ChipPtr chip_;
    gpiod_line* line_;
    GpioLineConfig cfg_;
};

}  // namespace

Result<std::unique_ptr<GpioInput>> open_gpiod_input(const GpioLineConfig& cfg) {
    auto chip = open_chip(cfg);
    if (!chip.ok()) return chip.error();
    auto line = get_line(chip.value().get(), cfg);
    if (!line.ok()) return line.error();
    if (gpiod_line_request_both_edges_events_flags(line.value(), cfg.consumer.c_str(), flags(cfg)) < 0)
        return request_error(cfg, errno);
    return std::unique_ptr<GpioInput>(std::make_unique<GpiodInput>(std::move(chip.value()), line.value(), cfg));
}

Result<std::unique_ptr<GpioOutput>> open_gpiod_output(const GpioLineConfig& cfg, bool initially_active) {
    auto chip = open_chip(cfg);
    if (!chip.ok()) return chip.error();
    auto line = get_line(chip.value().get(), cfg);
    if (!line.ok()) return line.error();
    if (gpiod_line_request_output_flags(line.value(), cfg.consumer.c_str(), flags(cfg), initially_active ? 1 : 0) < 0)
        return request_error(cfg, errno);
    return std::unique_ptr<GpioOutput>(std::make_unique<GpiodOutput>(std::move(chip.value()), line.value(), cfg));
}

}  // namespace rollsense::hal
