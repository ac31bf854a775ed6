#include "png_image.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace rollsense::test {

namespace {

std::uint32_t be32(const std::uint8_t* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

std::uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return static_cast<std::uint8_t>(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

}  // namespace

RgbImage read_png(const std::filesystem::path& file) {
    auto fail = [&](const std::string& what) { throw std::runtime_error("PNG '" + file.string() + "': " + what); };
    std::ifstream in(file, std::ios::binary);
    if (!in) fail("cannot be opened");
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    static const std::uint8_t signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    if (bytes.size() < 8 || !std::equal(signature, signature + 8, bytes.begin())) fail("no PNG signature");
    RgbImage img;
    int channels = 0;
    std::vector<std::uint8_t> idat;
    for (std::size_t pos = 8; pos + 12 <= bytes.size();) {
        const std::uint32_t len = be32(&bytes[pos]);
        const std::string type(bytes.begin() + static_cast<long>(pos) + 4, bytes.begin() + static_cast<long>(pos) + 8);
        if (pos + 12 + len > bytes.size()) fail("chunk " + type + " runs past the end of the file");
        const std::uint8_t* data = &bytes[pos + 8];
        if (type == "IHDR") {
            img.width = be32(data);
            img.height = be32(data + 4);
            const int depth = data[8], colour = data[9], interlace = data[12];
            if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0)
                fail("only 8-bit non-interlaced RGB/RGBA is supported (depth " + std::to_string(depth) +
                     ", colour type " + std::to_string(colour) + ")");
            channels = colour == 2 ? 3 : 4;
        } else if (type == "IDAT") {
            idat.insert(idat.end(), data, data + len);
        } else if (type == "IEND") {
            break;
        }
        pos += 12 + len;
    }
    if (channels == 0 || img.width == 0 || img.height == 0) fail("no image header or an empty image");
    const std::size_t stride = std::size_t{img.width} * static_cast<std::size_t>(channels);
    std::vector<std::uint8_t> raw((stride + 1) * img.height);
    uLongf raw_len = static_cast<uLongf>(raw.size());
    if (uncompress(raw.data(), &raw_len, idat.data(), static_cast<uLong>(idat.size())) != Z_OK || raw_len != raw.size())
        fail("image data does not inflate to " + std::to_string(raw.size()) + " bytes");
    std::vector<std::uint8_t> prev(stride, 0), cur(stride);
    img.rgb.reserve(std::size_t{img.width} * img.height * 3);
    for (std::uint32_t y = 0; y < img.height; ++y) {
        const std::uint8_t* line = &raw[y * (stride + 1)];
        const int filter = line[0];
        for (std::size_t i = 0; i < stride; ++i) {
            const int a = i >= static_cast<std::size_t>(channels) ? cur[i - static_cast<std::size_t>(channels)] : 0;
            const int b = prev[i];
            const int c = i >= static_cast<std::size_t>(channels) ? prev[i - static_cast<std::size_t>(channels)] : 0;
            int v = line[1 + i];
            switch (filter) {
                case 0: break;
                case 1: v += a; break;
                case 2: v += b; break;
                case 3: v += (a + b) / 2; break;
                case 4: v += paeth(a, b, c); break;
                default: fail("unknown filter type " + std::to_string(filter) + " on row " + std::to_string(y));
            }
            cur[i] = static_cast<std::uint8_t>(v);
        }
        for (std::uint32_t x = 0; x < img.width; ++x)
            for (int k = 0; k < 3; ++k) img.rgb.push_back(cur[x * static_cast<std::uint32_t>(channels) + static_cast<std::uint32_t>(k)]);
        std::swap(prev, cur);
    }
    return img;
}

}  // namespace rollsense::test
