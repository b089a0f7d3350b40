// theme.cpp — colour tables (RGBA, straight alpha).
#include "engine/render/theme.hpp"

namespace contactlab::render {

const Theme& dark_theme() {
    static const Theme t{
        .background = {24, 26, 31, 255},
        .grid_minor = {255, 255, 255, 18},
        .grid_major = {255, 255, 255, 44},
        .axis = {255, 255, 255, 90},
        .solid_fill = {92, 99, 112, 255},
        .contour = {214, 220, 229, 255},
        .finger_fill = {230, 180, 150, 70},
        .finger_outline = {240, 200, 170, 255},
        .pad = {255, 150, 60, 255},
        .proxy = {120, 200, 255, 170},
        .force = {255, 80, 80, 255},
        .contact = {255, 230, 60, 255},
        .target = {80, 255, 160, 255},
        .cspace = {230, 90, 255, 220},
        .anticipation = {80, 255, 160, 200},
        .zone_pad = {80, 160, 255, 40},
        .zone_proximal = {255, 120, 60, 40},
        .zone_distal = {120, 255, 120, 40},
        .legend = {220, 220, 220, 255},
        .cable = {80, 200, 255, 255},
    };
    return t;
}

const Theme& light_theme() {
    static const Theme t{
        .background = {248, 248, 244, 255},
        .grid_minor = {0, 0, 0, 16},
        .grid_major = {0, 0, 0, 40},
        .axis = {0, 0, 0, 90},
        .solid_fill = {176, 168, 152, 255},
        .contour = {40, 40, 44, 255},
        .finger_fill = {210, 150, 120, 80},
        .finger_outline = {120, 70, 50, 255},
        .pad = {220, 100, 20, 255},
        .proxy = {20, 110, 200, 170},
        .force = {210, 30, 30, 255},
        .contact = {200, 150, 0, 255},
        .target = {0, 150, 80, 255},
        .cspace = {170, 30, 200, 220},
        .anticipation = {0, 150, 80, 200},
        .zone_pad = {40, 110, 230, 36},
        .zone_proximal = {230, 100, 30, 36},
        .zone_distal = {40, 190, 60, 36},
        .legend = {30, 30, 30, 255},
        .cable = {0, 110, 190, 255},
    };
    return t;
}

std::optional<Theme> theme_by_name(std::string_view name) {
    if (name == "dark") return dark_theme();
    if (name == "light") return light_theme();
    return std::nullopt;
}

}  // namespace contactlab::render
