// Terminal logging for the CLI: "warning hand: message", levels chosen with -v / -q.
#pragma once

#include "cli/command.hpp"

namespace rollsense::cli {
// Reads -v/--verbose and -q/--quiet from args and installs the terminal sink.
void setup_logging(const Args& args);
}  // namespace rollsense::cli
