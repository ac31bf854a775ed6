// Just enough of a PNG decoder to judge a browser screenshot: 8-bit RGB or
// RGBA, non-interlaced (what Chromium writes), filters undone, pixels as RGB.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rollsense::test {

struct RgbImage {
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // width * height * 3
};

// Throws std::runtime_error naming the file and what is wrong with it.
RgbImage read_png(const std::filesystem::path& file);

}  // namespace rollsense::test
