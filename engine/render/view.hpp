// view.hpp — which part of the world a frame shows: world (m, y up) <-> pixels (origin top-left,
// y down; pixel (i, j) covers [i, i+1) x [j, j+1)).
#pragma once

#include "engine/render/draw_list.hpp"
#include "haptics/aabb_tree.hpp"

namespace contactlab::render {

struct View {
    int width = 1280, height = 720;  // px
    Vec2 center{0.0};                // world point at the image centre (m)
    double px_per_m = 2000.0;        // zoom

    P2 to_px(Vec2 w) const {
        return {static_cast<float>(0.5 * width + (w.x - center.x) * px_per_m),
                static_cast<float>(0.5 * height - (w.y - center.y) * px_per_m)};
    }
    Vec2 to_world(double px, double py) const {
        return {center.x + (px - 0.5 * width) / px_per_m, center.y - (py - 0.5 * height) / px_per_m};
    }
    // The world rectangle the image covers.
    Aabb world_bounds() const {
        Aabb b;
        b.grow(to_world(0.0, height));
        b.grow(to_world(width, 0.0));
        return b;
    }
};

// The view of `box` (m) centred in a width x height image with `margin` (a fraction of the image
// on every side) and equal scales on both axes. An empty or degenerate box gets 0.2 m across.
View fit_view(const Aabb& box, int width, int height, double margin = 0.06);

}  // namespace contactlab::render
