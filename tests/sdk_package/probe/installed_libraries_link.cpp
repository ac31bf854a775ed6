// Linked against the installed package only: one call into each library whose headers it installs beside the SDK.
#include <cstdio>

#include "rollsense/features.hpp"
#include "rollsense/hal/gpio.hpp"
#include "rollsense/hal/i2c.hpp"

int main() {
    const auto bus = rollsense::hal::open_i2c_bus("/dev/i2c-nonexistent");
    const auto lines = rollsense::hal::gpio_digital_lines();
    std::printf("%s %d %d\n", rollsense::features::feature_names()[0].c_str(), bus.ok() ? 1 : 0, lines.open_input ? 1 : 0);
    return 0;
}
