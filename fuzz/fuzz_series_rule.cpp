// The series rule a MiniRocket model file records (its `series_rule` line,
// read by analysis/src/analysis/series/model_rule.cpp when predict or
// rs.classifier loads the model): any text is refused or read, and what is
// read is written back as text that reads to the same settings.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "analysis/series/model_rule.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace rollsense::series;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const auto rule = parse_rule_text(text, "fuzz.rsm");
    if (!rule) return 0;
    const std::string written = rule_text(*rule);
    const auto again = parse_rule_text(written, "fuzz.rsm");
    if (!again || rule_text(*again) != written) rollsense::fuzz::invariant_broken("a rule read does not write back");
    return 0;
}
