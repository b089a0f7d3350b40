// camera.hpp — what part of the world the editor's canvas shows: pan, zoom about the cursor (the
// world point under the cursor stays under it), fit to the scene. Pure arithmetic on a View.
#pragma once

#include "engine/render/view.hpp"

namespace contactlab::editor {

class Camera {
public:
    const render::View& view() const { return view_; }
    // The canvas size changed (px): the centre and the zoom stay.
    void resize(int width, int height);
    // Drags the world by (dx, dy) px (the world moves with the cursor).
    void pan(double dx_px, double dy_px);
    // Multiplies px_per_m by `factor` keeping the world point under (cx, cy) px fixed. The zoom
    // stays within [kMinZoom, kMaxZoom] px/m.
    void zoom_at(double cx_px, double cy_px, double factor);
    // Shows `box` (m) with a margin (fit_view).
    void fit(const Aabb& box);

    static constexpr double kMinZoom = 20.0;    // px/m: 50 m across 1000 px
    static constexpr double kMaxZoom = 2.0e6;   // px/m: 0.5 um per px

private:
    render::View view_;
};

}  // namespace contactlab::editor
