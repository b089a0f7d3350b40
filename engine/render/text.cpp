// text.cpp — stb_easy_font quads -> DrawList rectangles.
#include "engine/render/text.hpp"

#include <cmath>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wconversion"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace contactlab::render {
namespace {

// stb_easy_font vertex: x, y, z (float) + RGBA, 16 bytes; 4 per quad.
struct EasyVertex {
    float x, y, z;
    unsigned char rgba[4];
};

}  // namespace

void draw_text(DrawList& out, P2 origin, const std::string& text, Color color, int scale) {
    if (text.empty()) return;
    std::string copy = text;  // the API takes char*; it knows printable ASCII only
    for (char& ch : copy)
        if (ch != '\n' && (ch < 32 || ch > 126)) ch = '?';
    std::vector<EasyVertex> quads(copy.size() * 4 * 70);  // ~270 bytes of quads per character
    const int n = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, quads.data(),
                                      static_cast<int>(quads.size() * sizeof(EasyVertex)));
    const P2 o(std::round(origin.x), std::round(origin.y));
    const float s = static_cast<float>(scale);
    for (int q = 0; q < n; ++q) {
        const EasyVertex& a = quads[4 * q];
        const EasyVertex& c = quads[4 * q + 2];
        out.fill_rect(o + P2(a.x, a.y) * s, o + P2(c.x, c.y) * s, color);
    }
}

P2 text_size(const std::string& text, int scale) {
    std::string copy = text;
    for (char& ch : copy)
        if (ch != '\n' && (ch < 32 || ch > 126)) ch = '?';
    return P2(static_cast<float>(stb_easy_font_width(copy.data())),
              static_cast<float>(stb_easy_font_height(copy.data()))) * static_cast<float>(scale);
}

}  // namespace contactlab::render
