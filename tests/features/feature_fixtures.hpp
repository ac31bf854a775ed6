// Shared by the feature tests: synthetic peaks and scratch folders.
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace rollsense::features::test {

// Triangle with its maximum `amp` at sample m, rising over `rise` samples and
// falling over `fall` samples, zero elsewhere.
inline std::vector<double> triangle(std::size_t n, double amp, long m, double rise, double fall) {
    std::vector<double> x(n, 0.0);
    for (long i = 0; i < static_cast<long>(n); ++i) {
        const double d = static_cast<double>(i - m);
        const double v = d <= 0 ? 1.0 + d / rise : 1.0 - d / fall;
        x[static_cast<std::size_t>(i)] = amp * std::max(0.0, v);
    }
    return x;
}

// A fresh, empty folder for one test ("rollsense-test-features-NAME-PID").
inline std::filesystem::path temp_dir(const std::string& name) {
    auto d = std::filesystem::temp_directory_path() /
             ("rollsense-test-features-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

}  // namespace rollsense::features::test
