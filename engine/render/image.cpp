// image.cpp — PNG in and out through Debian's libstb (-lstb; the implementations live there).
#include "engine/render/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace contactlab::render {

void write_png(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
        throw std::runtime_error("write_png: bad image for " + path);
    const std::string tmp = path + ".tmp";
    if (!stbi_write_png(tmp.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4)) {
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot write PNG " + path);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot write PNG " + path + ": " + ec.message());
    }
}

Image read_png(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!data) throw std::runtime_error("cannot read PNG " + path + ": " + stbi_failure_reason());
    Image img;
    img.width = w;
    img.height = h;
    img.rgba.assign(data, data + static_cast<size_t>(w) * h * 4);
    stbi_image_free(data);
    return img;
}

}  // namespace contactlab::render
