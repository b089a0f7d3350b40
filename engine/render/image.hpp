// image.hpp — an 8-bit RGBA picture in memory and its PNG files (stb_image_write / stb_image).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::render {

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;  // row-major, top row first, 4 bytes per pixel

    const uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
    uint8_t* pixel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

// Writes an RGBA PNG atomically (temporary file beside `path`, then rename). Throws on failure.
void write_png(const std::string& path, const Image& image);
// Reads any PNG as RGBA. Throws std::runtime_error when the file is missing or not a PNG.
Image read_png(const std::string& path);

}  // namespace contactlab::render
