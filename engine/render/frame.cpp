// frame.cpp — build_frame: the painter's order of a frame (parts in frame_*.cpp).
#include "engine/render/frame.hpp"

#include "engine/render/frame_parts.hpp"
#include "haptics/finger.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::render {

View default_view(const FrameContent& content, int width, int height) {
    Aabb box;
    if (content.env) box = content.env->bounds;
    if (content.finger) {
        // The finger's body reaches 2.5 R behind its centre and R around it.
        const double reach = 3.5 * content.shape.radius;
        box.grow(content.finger->finger - Vec2(reach));
        box.grow(content.finger->finger + Vec2(reach));
    }
    return fit_view(box, width, height);
}

Aabb fingertip_box(Vec2 finger, double phi, double radius) {
    const Vec2 pad_mid = finger + radius * unit_at(pad_mid_angle(phi));
    const double reach = 0.5 * radius;  // m
    Aabb box;
    box.grow(pad_mid - Vec2(reach));
    box.grow(pad_mid + Vec2(reach));
    return box;
}

View fingertip_view(const FrameContent& content, int width, int height) {
    return fit_view(fingertip_box(content.finger->finger, content.finger->phi, content.shape.radius), width, height);
}

namespace parts {

Metrics metrics_for(const View& view) {
    // Sizes follow the image's short side so small test images stay legible (px).
    const float s = static_cast<float>(std::min(view.width, view.height)) / 720.0f;
    Metrics m;
    m.contour_width = std::max(1.5f, 2.5f * s);
    m.outline_width = std::max(1.0f, 2.0f * s);
    m.pad_width = std::max(2.0f, 5.0f * s);
    m.dot_radius = std::max(2.0f, 5.0f * s);
    m.arrow_full = std::max(24.0f, 140.0f * s);
    m.arrow_width = std::max(1.5f, 3.5f * s);
    m.text_scale = std::max(1, static_cast<int>(std::lround(2.0f * s)));
    return m;
}

}  // namespace parts

void build_scene_layer(const FrameContent& content, const View& view, const Theme& theme, DrawList& out) {
    const parts::Metrics m = parts::metrics_for(view);
    parts::draw_grid(view, theme, out);
    if (scene_layer_follows_finger(content)) parts::draw_zones(content, view, theme, out);
    if (content.scene) parts::draw_solids(*content.scene, view, theme, m, out);
}

void build_overlay_layer(const FrameContent& content, const View& view, const Theme& theme, DrawList& out,
                         LabelMarks* placed) {
    const parts::Metrics m = parts::metrics_for(view);
    if (content.overlays.cspace && content.finger && content.env) parts::draw_cspace(content, view, theme, m, out);
    // The labels' room: the canvas less the insets (the editor's panels), less the legend's boxes
    // and the status line, which keep their fixed places.
    LabelMarks marks;
    marks.area = {{content.left_inset_px, content.top_inset_px},
                  {static_cast<float>(view.width) - content.right_inset_px,
                   static_cast<float>(view.height) - content.bottom_inset_px}};
    const LegendLayout legend = legend_layout(content, view);
    auto box_of = [](const PxBox& b) { return LabelBox{{b.x, b.y}, {b.x + b.w, b.y + b.h}}; };
    marks.texts.push_back(box_of(legend.scale_bar));
    if (legend.force_bar) marks.texts.push_back(box_of(*legend.force_bar));
    if (legend.platform_key) marks.texts.push_back(box_of(*legend.platform_key));
    if (legend.status_line) marks.texts.push_back(box_of(*legend.status_line));
    else if (content.text && content.finger && content.status_line) marks.dropped.push_back("status line");
    if (content.finger) parts::draw_proxy_state(content, view, theme, m, out, marks);
    parts::draw_legend(content, view, theme, m, legend, out);  // the same layout: its placement drew the marks once
    if (placed) *placed = std::move(marks);
}

bool scene_layer_follows_finger(const FrameContent& content) {
    return content.overlays.zones && content.finger && content.env;
}

void build_frame(const FrameContent& content, const View& view, const Theme& theme, DrawList& out,
                 LabelMarks* placed) {
    out.clear();
    build_scene_layer(content, view, theme, out);
    build_overlay_layer(content, view, theme, out, placed);
}

}  // namespace contactlab::render
