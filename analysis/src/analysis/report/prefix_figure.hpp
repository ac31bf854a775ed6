// The report's "before the roll ends" section: accuracy against the share of
// the nominal roll and against seconds of rolling, per classifier and speed.
#pragma once

#include <string>

#include "analysis/learn/prefix_curves.hpp"

namespace rollsense::report {

// Section body (figures, table, the timing-rule statement).
std::string prefix_section(const learn::PrefixCurves& curves);

}  // namespace rollsense::report
