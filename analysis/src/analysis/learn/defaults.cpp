#include "analysis/learn/defaults.hpp"

#include <fstream>

namespace rollsense::learn {
namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return {};
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

}  // namespace

std::filesystem::path defaults_file(const std::filesystem::path& share_dir) {
    return share_dir / "analysis" / "defaults.csv";
}

Result<std::string> analysis_default(const std::filesystem::path& share_dir, const std::string& key) {
    const auto file = defaults_file(share_dir);
    std::ifstream in(file);
    if (!in)
        return Error{ErrorCode::not_found, "analysis defaults '" + file.string() +
                                               "' cannot be opened; is the share folder right (set ROLLSENSE_SHARE)? "
                                               "Or name it explicitly (e.g. --classifier NAME)"};
    std::string line;
    bool header = false;
    for (int no = 1; std::getline(in, line); ++no) {
        const std::string t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        const auto where = file.string() + ":" + std::to_string(no);
        const auto comma = t.find(',');
        if (comma == std::string::npos || t.find(',', comma + 1) != std::string::npos)
            return Error{ErrorCode::parse_error, where + ": expected 'key,value', got '" + t + "'"};
        const std::string k = trim(t.substr(0, comma)), v = trim(t.substr(comma + 1));
        if (!header) {
            if (k != "key" || v != "value")
                return Error{ErrorCode::parse_error, where + ": the first row must be the header 'key,value'"};
            header = true;
            continue;
        }
        if (k != key) continue;
        if (v.empty()) return Error{ErrorCode::parse_error, where + ": '" + key + "' has an empty value"};
        return v;
    }
    return Error{ErrorCode::not_found,
                 "analysis defaults '" + file.string() + "' has no '" + key + "' row; add '" + key + ",VALUE'"};
}

Result<std::string> default_classifier(const std::filesystem::path& share_dir) {
    return analysis_default(share_dir, "classifier");
}

Result<std::string> classifier_or_default(const std::string& given, const std::filesystem::path& share_dir) {
    if (!given.empty()) return given;
    return default_classifier(share_dir);
}

std::string with_default_classifier(std::string text, const std::filesystem::path& share_dir) {
    static const std::string placeholder = "{default_classifier}";
    const auto d = default_classifier(share_dir);
    const std::string value = d ? *d : "none: " + d.error().message;
    for (auto at = text.find(placeholder); at != std::string::npos; at = text.find(placeholder, at + value.size()))
        text.replace(at, placeholder.size(), value);
    return text;
}

}  // namespace rollsense::learn
