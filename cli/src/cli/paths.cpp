#include "cli/paths.hpp"

#include <cstdlib>

#include <boost/dll/runtime_symbol_info.hpp>

namespace rollsense::cli {
namespace fs = std::filesystem;

fs::path share_dir() {
    if (const char* env = std::getenv("ROLLSENSE_SHARE")) return env;
    std::error_code ec;
    auto exe = fs::path(boost::dll::program_location().string());
    auto installed = exe.parent_path().parent_path() / "share" / "rollsense";
    if (fs::exists(installed / "profiles", ec)) return installed;
    return ROLLSENSE_SOURCE_SHARE_DIR;
}

fs::path resolve_script(const fs::path& script) {
    std::error_code ec;
    if (fs::exists(script, ec) || script.is_absolute()) return script;
    for (const auto& base : {share_dir() / "scripts", fs::path(ROLLSENSE_SOURCE_SCRIPTS_DIR).parent_path()}) {
        if (fs::exists(base / script, ec)) return base / script;
    }
    return script;
}

}  // namespace rollsense::cli
