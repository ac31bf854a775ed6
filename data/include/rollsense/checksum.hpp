// The checksum line of rollsense's text file formats (the classifier model
// files): FNV-1a 64 of every byte before the line, as 16 lower-case hex
// digits. It catches truncation and damage; it is not a cryptographic seal.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace rollsense {

inline std::string fnv1a_hex(std::string_view bytes) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 0x100000001b3ULL;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

}  // namespace rollsense
