// theme.hpp — the colours of a frame. Two themes, dark (default) and light.
#pragma once

#include "engine/render/draw_list.hpp"

#include <optional>
#include <string_view>

namespace contactlab::render {

struct Theme {
    Color background;
    Color grid_minor, grid_major, axis;
    Color solid_fill, contour;
    Color finger_fill, finger_outline, pad;
    Color proxy;
    Color force, contact, target;
    Color cspace, anticipation;
    Color zone_pad, zone_proximal, zone_distal;  // anticipation zones: pad interior, pad ends
    Color legend;
    // Seed 003's cables and their tension arrows: their own colour, never the force arrow's red
    // (issue 29: the two were told apart by nothing).
    Color cable;
};

const Theme& dark_theme();
const Theme& light_theme();
// "dark" or "light"; nullopt otherwise.
std::optional<Theme> theme_by_name(std::string_view name);

}  // namespace contactlab::render
