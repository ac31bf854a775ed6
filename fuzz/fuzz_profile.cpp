// Profiles and settings (kernel/src/runtime/profile/profile.cpp): the input
// up to its first NUL byte is a profile file, the rest one `--set key=value`
// per line. The harness targets the value checks of the profile table, not
// the Lua interpreter: inputs with loops, function definitions or string
// repetition are skipped (a script-shaped profile's running time and memory
// are the Lua sandbox's hook and cap, not a parser's bounds).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "runtime/profile/profile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view in(reinterpret_cast<const char*>(data), size);
    const auto nul = in.find('\0');
    const std::string_view profile = in.substr(0, nul);
    for (std::string_view word : {"while", "repeat", "for", "goto", "function", "rep", "load", "require"})
        if (profile.find(word) != std::string_view::npos) return 0;
    rollsense::runtime::Settings settings;
    if (nul != std::string_view::npos) {
        std::string_view rest = in.substr(nul + 1);
        while (!rest.empty()) {
            const auto nl = rest.find('\n');
            (void)settings.add(std::string(rest.substr(0, nl)));
            if (nl == std::string_view::npos) break;
            rest.remove_prefix(nl + 1);
        }
    }
    const auto file = rollsense::fuzz::scratch_dir() / "profile.lua";
    rollsense::fuzz::write_file(file, profile);
    (void)rollsense::runtime::load_profile(file.string(), ROLLSENSE_FUZZ_SHARE_DIR, settings);
    return 0;
}
