// Where the program finds its data: $ROLLSENSE_SHARE, else <prefix>/share/rollsense
// next to the installed program, else the source tree's share/ (build tree).
#pragma once

#include <filesystem>

namespace rollsense::cli {
std::filesystem::path share_dir();
// A script named without a folder that does not exist in the working
// directory is looked up in <share>/scripts and the source scripts/ folder.
std::filesystem::path resolve_script(const std::filesystem::path& script);
}  // namespace rollsense::cli
