#include "rollsense/trial_id.hpp"

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

}  // namespace rollsense
