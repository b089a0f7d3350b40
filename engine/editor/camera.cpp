// camera.cpp — pan, cursor-anchored zoom, fit (see camera.hpp).
#include "engine/editor/camera.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::editor {

void Camera::resize(int width, int height) {
    view_.width = std::max(1, width);
    view_.height = std::max(1, height);
}

void Camera::pan(double dx_px, double dy_px) {
    view_.center.x -= dx_px / view_.px_per_m;
    view_.center.y += dy_px / view_.px_per_m;  // pixel y grows downward, world y upward
}

void Camera::zoom_at(double cx_px, double cy_px, double factor) {
    if (!(factor > 0.0) || !std::isfinite(factor)) return;
    const Vec2 anchor = view_.to_world(cx_px, cy_px);
    view_.px_per_m = std::clamp(view_.px_per_m * factor, kMinZoom, kMaxZoom);
    // Move the centre so `anchor` maps back to (cx, cy).
    view_.center.x = anchor.x - (cx_px - 0.5 * view_.width) / view_.px_per_m;
    view_.center.y = anchor.y + (cy_px - 0.5 * view_.height) / view_.px_per_m;
}

void Camera::fit(const Aabb& box) {
    view_ = render::fit_view(box, view_.width, view_.height);
    view_.px_per_m = std::clamp(view_.px_per_m, kMinZoom, kMaxZoom);
}

}  // namespace contactlab::editor
