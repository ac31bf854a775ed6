// Terminal logging for the CLI: "warning hand: message", levels chosen with
// -v / -q; coloured only where colour_allowed() (a terminal, no NO_COLOR);
// prefixed with the UTC time under the global --log-time (main.cpp).
#pragma once

#include "cli/command.hpp"

namespace rollsense::cli {
// Reads -v/--verbose and -q/--quiet from args and installs the terminal sink.
void setup_logging(const Args& args);
}  // namespace rollsense::cli
