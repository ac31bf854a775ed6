// Digital lines the kernel itself uses: the emergency-stop input it checks every control period and the trigger
// output it pulses when a recording starts. The kernel sees only these interfaces; the program hands it a
// DigitalLines that opens real lines (the HAL's libgpiod backend, or its fake chips in tests), so the kernel never
// depends on an I/O library.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "rollsense/status.hpp"

namespace rollsense {

struct DigitalLine {
    std::string chip;  // as the provider names chips, e.g. "gpiochip0" or "fake:<name>"
    unsigned line = 0;
    bool active_low = false;
    std::string consumer = "rollsense";  // shown to other users of the line
};

class DigitalInput {
public:
    virtual ~DigitalInput() = default;
    // The logical level now (active_low applied); does not block.
    virtual Result<bool> is_active() = 0;
};

class DigitalOutput {
public:
    virtual ~DigitalOutput() = default;
    virtual Status set_active(bool active) = 0;
};

// How to open lines. Either function may be empty: a profile that asks for a
// line then fails to start with an error saying no provider is available.
struct DigitalLines {
    std::function<Result<std::unique_ptr<DigitalInput>>(const DigitalLine&)> open_input;
    std::function<Result<std::unique_ptr<DigitalOutput>>(const DigitalLine&, bool initially_active)> open_output;
};

}  // namespace rollsense
