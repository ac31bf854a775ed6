#include "cli/run_dataset.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "rollsense/checksum.hpp"

namespace rollsense::cli {
namespace fs = std::filesystem;

namespace {
std::string file_digest(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return "(unreadable)";
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return fnv1a_hex(bytes.str());
}
}  // namespace

RunConfig run_config_of(const fs::path& script, const std::string& profile, const fs::path& profile_file,
                        std::uint64_t seed, const SetOptions& sets) {
    RunConfig config{{"rollsense_version", ROLLSENSE_VERSION_STRING},
                     {"script", script.filename().string()},
                     {"script_fnv1a", file_digest(script)},
                     {"profile", profile},
                     {"profile_fnv1a", file_digest(profile_file)},
                     {"seed", std::to_string(seed)}};
    std::map<std::string, std::string> last;
    for (const auto& [key, value] : sets) last[key] = value;
    for (const auto& [key, value] : last) config.emplace_back("set." + key, value);
    return config;
}

std::string shell_quote(const std::string& text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("_-./=,:+@%").find(c) != std::string_view::npos;
    });
    if (plain) return text;
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string resume_command(const std::string& script, const fs::path& out,
                           const std::vector<std::pair<std::string, std::string>>& options) {
    std::string line = "rollsense run " + shell_quote(script) + " --out " + shell_quote(out.string()) + " --resume";
    for (const auto& [option, value] : options) line += " " + option + " " + shell_quote(value);
    return line;
}

bool remove_empty_dataset(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return false;
    if (fs::exists(dir / "trials", ec) && !fs::is_empty(dir / "trials", ec)) return false;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const auto name = entry.path().filename().string();
        if (name != "trials" && name != "manifest.csv" && name != "dataset-info.csv" && name != "run-info.csv" &&
            name != kRunConfigFile)
            return false;
    }
    if (ec) return false;
    return fs::remove_all(dir, ec) > 0 && !ec;
}

}  // namespace rollsense::cli
