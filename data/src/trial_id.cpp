#include "rollsense/trial_id.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>

namespace rollsense {

std::string trial_id(std::string_view object, std::string_view speed, int repetition) {
    char rep[16];
    std::snprintf(rep, sizeof rep, "%03d", repetition);
    std::string id;
    id.reserve(object.size() + speed.size() + 8);
    id.append(object).append("-v").append(speed).append("-r").append(rep);
    return id;
}

namespace {

bool allowed(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '-';
}

// Names Windows refuses as a file's stem, whatever the extension.
bool reserved(std::string_view id) {
    std::string stem(id.substr(0, id.find('.')));
    for (auto& c : stem) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    static const std::array<const char*, 4> plain{"CON", "PRN", "AUX", "NUL"};
    if (std::find_if(plain.begin(), plain.end(), [&](const char* r) { return stem == r; }) != plain.end()) return true;
    return stem.size() == 4 && (stem.rfind("COM", 0) == 0 || stem.rfind("LPT", 0) == 0) && stem[3] >= '1' &&
           stem[3] <= '9';
}

}  // namespace

Status check_trial_info(const TrialInfo& info) {
    if (auto s = check_trial_id(info.id); !s.ok()) return s;
    for (const auto& [key, value] : info.extra) {
        const bool own_column = std::find(kProtocolKeys.begin(), kProtocolKeys.end(), key) != kProtocolKeys.end();
        if (key.empty() || key.find_first_of("=;") != std::string::npos ||
            (!own_column && value.find(';') != std::string::npos))
            return {ErrorCode::invalid_argument,
                    "trial '" + info.id + "': extra '" + key.substr(0, 60) + "' = '" + value.substr(0, 60) +
                        "' cannot go into the manifest's extra column (key=value;key=value) and read back the same: "
                        "give a key without '=' or ';' and a value without ';'"};
    }
    return {};
}

Status check_trial_id(std::string_view id) {
    const std::string shown = id.size() > 60 ? std::string(id.substr(0, 60)) + "..." : std::string(id);
    const std::string how = "; name it with 1 to " + std::to_string(kMaxTrialIdLength) +
                            " characters of A-Z a-z 0-9 . _ - (it names the file trials/<id>.csv)";
    if (id.empty()) return {ErrorCode::invalid_argument, "a trial id must not be empty" + how};
    if (id.size() > kMaxTrialIdLength)
        return {ErrorCode::invalid_argument, "trial id '" + shown + "' is " + std::to_string(id.size()) +
                                                 " characters long, more than " + std::to_string(kMaxTrialIdLength) +
                                                 how};
    if (const auto bad = std::find_if_not(id.begin(), id.end(), allowed); bad != id.end()) {
        const unsigned char c = static_cast<unsigned char>(*bad);
        char shown_char[8];
        if (c >= 0x21 && c < 0x7F) std::snprintf(shown_char, sizeof shown_char, "'%c'", c);
        else std::snprintf(shown_char, sizeof shown_char, "0x%02X", c);
        return {ErrorCode::invalid_argument,
                "trial id '" + shown + "' contains " + shown_char + " at position " +
                    std::to_string(bad - id.begin() + 1) + how};
    }
    if (id.front() == '.')
        return {ErrorCode::invalid_argument, "trial id '" + shown + "' starts with '.' (a hidden file)" + how};
    if (reserved(id))
        return {ErrorCode::invalid_argument, "trial id '" + shown + "' is a device name reserved on Windows" + how};
    return {};
}

}  // namespace rollsense
