// Shared by the harnesses: the readers under test take file paths, so each
// input is written to a per-process scratch folder on tmpfs (/dev/shm when it
// exists: no disk I/O per execution), and the model files' checksum is
// recomputed so inputs reach the structure checks behind it.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace rollsense::fuzz {

inline const std::filesystem::path& scratch_dir() {
    static const std::filesystem::path dir = [] {
        std::filesystem::path base = std::filesystem::exists("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                                          : std::filesystem::temp_directory_path();
        auto d = base / ("rollsense-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        // libFuzzer ends with exit(): remove the folder then.
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(scratch_dir(), ec);
        });
        return d;
    }();
    return dir;
}

inline void write_file(const std::filesystem::path& file, std::string_view text) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

// The model files' checksum line (FNV-1a 64 of every byte before it).
inline std::string checksum_line(std::string_view body) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : body) h = (h ^ c) * 0x100000001b3ULL;
    char buf[32];
    std::snprintf(buf, sizeof buf, "checksum %016llx\n", static_cast<unsigned long long>(h));
    return buf;
}

// A finding the sanitizers would not flag: a broken invariant.
[[noreturn]] inline void invariant_broken(const char* what) {
    std::fprintf(stderr, "invariant broken: %s\n", what);
    std::abort();
}

}  // namespace rollsense::fuzz
