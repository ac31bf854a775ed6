// GPIO lines: an emergency-stop input, a trigger output.
//
// Two backends behind one API:
//   chip "gpiochip0" or "/dev/gpiochip0" → libgpiod 1.6 (v1 API) on the GPIO
//       character device;
//   chip "fake:<name>"                    → FakeGpioChip, shared process-wide
//       by name so a test can drive the same chip the kernel opened.
// "Active" is the logical level: with active_low the physical level is
// inverted (an e-stop that pulls the line low reads active when pressed).
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "rollsense/digital_io.hpp"
#include "rollsense/status.hpp"

namespace rollsense::hal {

// chip: "gpiochip0", "/dev/gpiochip0" or "fake:<name>"; consumer is shown by gpioinfo.
using GpioLineConfig = DigitalLine;

class GpioInput : public DigitalInput {
public:
    // Wait up to `timeout` for an edge (either direction) and consume it.
    // true = an edge came, false = the timeout passed. A zero timeout polls.
    virtual Result<bool> wait_for_edge(std::chrono::milliseconds timeout) = 0;
};

class GpioOutput : public DigitalOutput {};

Result<std::unique_ptr<GpioInput>> open_gpio_input(const GpioLineConfig& config);
Result<std::unique_ptr<GpioOutput>> open_gpio_output(const GpioLineConfig& config, bool initially_active);

// The kernel's view of these lines (e-stop, trigger): open_gpio_input/output.
DigitalLines gpio_digital_lines();

// The libgpiod backend directly (open_gpio_* dispatch here for non-fake chips).
Result<std::unique_ptr<GpioInput>> open_gpiod_input(const GpioLineConfig& config);
Result<std::unique_ptr<GpioOutput>> open_gpiod_output(const GpioLineConfig& config, bool initially_active);

// An in-process GPIO chip. Levels here are physical (what a voltmeter on the
// pin would show); the line handles apply active_low like the kernel does.
// Like the kernel, a line can be requested by one consumer at a time.
class FakeGpioChip : public std::enable_shared_from_this<FakeGpioChip> {
public:
    // The chip of that name, created on first use (process-wide).
    static std::shared_ptr<FakeGpioChip> get(const std::string& name);

    explicit FakeGpioChip(std::string name, unsigned lines = 64);
    const std::string& name() const { return name_; }
    unsigned line_count() const { return lines_; }

    // ---- the outside world ----
    // Drive an input pin; a change of level queues an edge for a requested input.
    void set_input_level(unsigned line, bool level);
    // The physical level an output drives (false if never driven).
    bool output_level(unsigned line) const;
    // Every level an output was set to, in order (including the initial one).
    std::vector<std::pair<unsigned, bool>> output_history() const;
    void clear_output_history();
    // Who holds a line ("" = free), like gpioinfo's consumer column.
    std::string consumer(unsigned line) const;
    // Forget levels, requests' queued edges and history (requests stay).
    void reset();

    // ---- used by the line handles ----
    Status request(unsigned line, const std::string& consumer, bool output);
    void release(unsigned line);
    bool input_level(unsigned line) const;
    void drive(unsigned line, bool level);
    // Wait for a queued edge on `line`; consumes it.
    bool wait_edge(unsigned line, std::chrono::milliseconds timeout);

private:
    struct Line {
        bool level = false;
        bool requested = false;
        bool output = false;
        std::string consumer;
        int pending_edges = 0;
    };

    std::string name_;
    unsigned lines_;
    mutable std::mutex mutex_;
    std::condition_variable edge_cv_;
    std::map<unsigned, Line> state_;
    std::vector<std::pair<unsigned, bool>> history_;
};

}  // namespace rollsense::hal
