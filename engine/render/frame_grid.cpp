// frame_grid.cpp — the millimetre grid, the axes, and the legend (scale bar, force bar).
#include "engine/render/frame_parts.hpp"

#include "engine/render/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace contactlab::render::parts {
namespace {

// Grid step (m): 1, 2 or 5 times a power of ten mm, the smallest at least 8 px apart.
double grid_step(double px_per_m) {
    for (double decade = 1e-3;; decade *= 10.0)
        for (double k : {1.0, 2.0, 5.0})
            if (k * decade * px_per_m >= 8.0) return k * decade;
}

// Snaps a pixel coordinate to the centre of its pixel, so 1 px lines are crisp.
float snap(float v) { return std::floor(v) + 0.5f; }

}  // namespace

void draw_grid(const View& view, const Theme& theme, DrawList& out) {
    const double step = grid_step(view.px_per_m);
    const Aabb b = view.world_bounds();
    const float w = static_cast<float>(view.width), h = static_cast<float>(view.height);
    // Vertical lines; every 10th (or every 5th for a 5-mm-type step) is a major line, x = 0 the axis.
    const long long i0 = static_cast<long long>(std::ceil(b.lo.x / step));
    const long long i1 = static_cast<long long>(std::floor(b.hi.x / step));
    for (long long i = i0; i <= i1; ++i) {
        const float x = snap(view.to_px({static_cast<double>(i) * step, 0.0}).x);
        const Color c = i == 0 ? theme.axis : (i % 10 == 0 ? theme.grid_major : theme.grid_minor);
        out.line({x, 0.0f}, {x, h}, 1.0f, c);
    }
    const long long j0 = static_cast<long long>(std::ceil(b.lo.y / step));
    const long long j1 = static_cast<long long>(std::floor(b.hi.y / step));
    for (long long j = j0; j <= j1; ++j) {
        const float y = snap(view.to_px({0.0, static_cast<double>(j) * step}).y);
        const Color c = j == 0 ? theme.axis : (j % 10 == 0 ? theme.grid_major : theme.grid_minor);
        out.line({0.0f, y}, {w, y}, 1.0f, c);
    }
}

void draw_legend(const FrameContent& c, const View& view, const Theme& theme, const Metrics& m, const LegendLayout& l,
                 DrawList& out) {
    const float tick = 2.0f * m.dot_radius;
    {  // Scale bar: its line along the box's bottom, the label above its left end.
        const PxBox& b = l.scale_bar;
        const float y = b.y + b.h, x0 = b.x, x1 = x0 + static_cast<float>(l.scale_bar_m * view.px_per_m);
        out.line({x0, y}, {x1, y}, m.outline_width, theme.legend);
        out.line({x0, y - tick}, {x0, y}, m.outline_width, theme.legend);
        out.line({x1, y - tick}, {x1, y}, m.outline_width, theme.legend);
        if (c.text) {
            char label[32];
            std::snprintf(label, sizeof label, "%g mm", l.scale_bar_m * 1e3);
            draw_text(out, {x0, b.y}, label, theme.legend, m.text_scale);
        }
    }
    if (l.force_bar) {  // the arrow length of the maximum force (c.max_force N), right-aligned
        const PxBox& b = *l.force_bar;
        const float y = b.y + b.h, xr = b.x + b.w;
        out.line({xr - m.arrow_full, y}, {xr, y}, m.arrow_width, theme.force);
        out.line({xr - m.arrow_full, y - tick}, {xr - m.arrow_full, y}, m.outline_width, theme.force);
        out.line({xr, y - tick}, {xr, y}, m.outline_width, theme.force);
        if (c.text) {
            char label[32];
            std::snprintf(label, sizeof label, "%.2f N", c.max_force);
            const P2 size = text_size(label, m.text_scale);
            draw_text(out, {xr - size.x, b.y}, label, theme.force, m.text_scale);
        }
    }
    draw_platform_key(c, theme, m, l, out);  // the wearable's colours, with the text
    // Status line, top left: the proxy's state in the UI's units (mm, N, degrees).
    if (l.status_line) draw_text(out, {l.status_line->x, l.status_line->y}, proxy_status_text(*c.finger).c_str(), theme.legend, m.text_scale);
}

}  // namespace contactlab::render::parts

namespace contactlab::render {
namespace {

constexpr float kKeySwatch = 12.0f;  // px (times the text scale) of each key entry's colour line

// The wearable's key: what each colour means and the arrows' full lengths.
std::vector<std::string> platform_key_lines(const FrameContent& c) {
    char cable[96], force[96];
    std::snprintf(cable, sizeof cable, "cable tension (full arrow %.2f N)", c.platform->full_tension);
    std::snprintf(force, sizeof force, "force on the finger (full arrow %.2f N)", c.max_force);
    return {cable, force};
}

}  // namespace

void parts::draw_platform_key(const FrameContent& c, const Theme& theme, const parts::Metrics& m, const LegendLayout& l,
                              DrawList& out) {
    if (!l.platform_key) return;
    const float pad = std::round(m.dot_radius * 2.0f), s = static_cast<float>(m.text_scale);
    const PxBox& b = *l.platform_key;
    out.fill_rect({b.x, b.y}, {b.x + b.w, b.y + b.h}, theme.background.with_alpha(200));
    float y = b.y + 0.5f * pad;
    const Color colours[2] = {theme.cable, theme.force};
    int i = 0;
    for (const std::string& line : platform_key_lines(c)) {
        const P2 sz = text_size(line, m.text_scale);
        out.line({b.x + pad, y + 0.5f * sz.y}, {b.x + pad + kKeySwatch * s - 3.0f * s, y + 0.5f * sz.y}, m.arrow_width,
                 colours[i++]);
        draw_text(out, {b.x + pad + kKeySwatch * s, y}, line, theme.legend, m.text_scale);
        y += sz.y + 4.0f * s;
    }
}

LegendLayout legend_layout(const FrameContent& c, const View& view) {
    const parts::Metrics m = parts::metrics_for(view);
    LegendLayout l;
    // 10 mm (or 1 mm / 100 mm if that fits better), with end ticks.
    l.scale_bar_m = 0.01;
    if (l.scale_bar_m * view.px_per_m > 0.3 * view.width) l.scale_bar_m = 0.001;
    if (l.scale_bar_m * view.px_per_m < 12.0) l.scale_bar_m = 0.1;
    const float pad = std::round(m.dot_radius * 2.0f);
    const float y = static_cast<float>(view.height) - c.bottom_inset_px - pad;  // the bars' line
    const float label_gap = 2.0f * m.dot_radius + 3.0f * static_cast<float>(m.text_scale);
    char label[32];
    std::snprintf(label, sizeof label, "%g mm", l.scale_bar_m * 1e3);
    P2 size = c.text ? text_size(label, m.text_scale) : P2{0.0f, 0.0f};
    float top = y - (c.text ? label_gap + size.y : 2.0f * m.dot_radius);
    const float bar_w = static_cast<float>(l.scale_bar_m * view.px_per_m);
    l.scale_bar = {c.left_inset_px + pad, top, std::max(bar_w, size.x), y - top};
    if (c.finger) {
        std::snprintf(label, sizeof label, "%.2f N", c.max_force);
        size = c.text ? text_size(label, m.text_scale) : P2{0.0f, 0.0f};
        top = y - (c.text ? label_gap + size.y : 2.0f * m.dot_radius);
        const float w = std::max(m.arrow_full, size.x);
        const float xr = static_cast<float>(view.width) - c.right_inset_px - pad;
        l.force_bar = PxBox{xr - w, top, w, y - top};
    }
    // What the status line and the key must not cover: the finger's marks (outline, pad, cables,
    // arrows, platform), drawn into a scratch list with the text off (no labels, no legend: no
    // recursion back here).
    const bool status_wanted = c.text && c.finger && c.status_line;
    LabelMarks marks;
    marks.area = {{c.left_inset_px, c.top_inset_px},
                  {static_cast<float>(view.width) - c.right_inset_px, static_cast<float>(view.height) - c.bottom_inset_px}};
    if (c.finger && (status_wanted || (c.platform && c.text))) {
        FrameContent bare = c;
        bare.text = false;
        DrawList scratch(view.width, view.height);
        parts::draw_proxy_state(bare, view, dark_theme(), m, scratch, marks);
    }
    // Free of the finger's marks, the text placed so far and the contour under the box (the
    // environment's pieces there, asked of its tree: a dense scene costs only what lies under it).
    auto is_free = [&](const LabelBox& box) {
        if (!marks.free(box, kLabelClearance)) return false;
        if (!c.env) return true;
        LabelMarks contour;
        const float reach = kLabelClearance + m.contour_width;
        parts::add_contour_marks(*c.env, view, LabelBox{box.lo - P2(reach), box.hi + P2(reach)}, m.contour_width, contour);
        contour.area = marks.area;
        return contour.free(box, kLabelClearance);
    };
    if (c.platform && c.text) {
        float w = 0.0f, h = 0.0f;
        for (const std::string& line : platform_key_lines(c)) {
            const P2 sz = text_size(line, m.text_scale);
            w = std::max(w, sz.x);
            h += sz.y + 4.0f * static_cast<float>(m.text_scale);
        }
        w += kKeySwatch * static_cast<float>(m.text_scale) + 2.0f * pad;
        h += pad;
        const float xr = static_cast<float>(view.width) - c.right_inset_px - pad;
        // The key sits on no data and no text: the first corner of the canvas whose box crosses
        // none of the finger's marks (the cables run up to the nail side, often through the top
        // right): top right, top left, bottom left above the scale bar,
        // bottom right above the force bar; else the top right. A canvas narrower than the key
        // (the editor's, between its panels) gets it across.
        const float x_right = xr - w, x_left = std::min(c.left_inset_px + pad, x_right);
        marks.area.lo.x = std::min(marks.area.lo.x, x_right);
        const float top_y = c.top_inset_px + pad;
        const P2 corners[] = {{x_right, top_y}, {x_left, top_y}, {x_left, l.scale_bar.y - pad - h},
                              {x_right, (l.force_bar ? l.force_bar->y : l.scale_bar.y) - pad - h}};
        P2 at = corners[0];
        for (const P2& t : corners)
            if (is_free(LabelBox{t, t + P2(w, h)})) {
                at = t;
                break;
            }
        l.platform_key = PxBox{at.x, at.y, w, h};
        marks.texts.push_back(LabelBox{at, at + P2(w, h)});
    }
    // The status line, after the key: top left, else above the scale bar, else above the force
    // bar, else top right, else above the key and the scale bar; else it is left out (the CLI
    // prints the same state; the zoomed wearable's cables run up through the top of the picture).
    if (status_wanted) {
        const P2 size = text_size(proxy_status_text(*c.finger), m.text_scale);
        const float xr = static_cast<float>(view.width) - c.right_inset_px - pad;
        const float above_left = (l.platform_key ? std::min(l.platform_key->y, l.scale_bar.y) : l.scale_bar.y) - pad - size.y;
        const P2 tries[] = {{c.left_inset_px + pad, c.top_inset_px + pad},
                            {c.left_inset_px + pad, l.scale_bar.y - pad - size.y},
                            {xr - size.x, (l.force_bar ? l.force_bar->y : l.scale_bar.y) - pad - size.y},
                            {xr - size.x, c.top_inset_px + pad},
                            {c.left_inset_px + pad, above_left}};
        for (const P2& t : tries)
            if (is_free(LabelBox{t, t + size})) {
                l.status_line = PxBox{t.x, t.y, size.x, size.y};
                break;
            }
    }
    return l;
}

std::string proxy_status_text(const ProxyOutput& o) {
    char status[160];
    if (o.contact)
        std::snprintf(status, sizeof status, "x_f (%.1f, %.1f) mm  phi %.1f deg  contacts %d  |F| %.3f N  l_d %+.2f mm",
                      o.finger.x * 1e3, o.finger.y * 1e3, o.phi * 180.0 / kPi, o.contact_count, glm::length(o.force),
                      o.l_d * 1e3);
    else
        std::snprintf(status, sizeof status, "x_f (%.1f, %.1f) mm  phi %.1f deg  free  anticipated l_d %+.2f mm",
                      o.finger.x * 1e3, o.finger.y * 1e3, o.phi * 180.0 / kPi, o.l_d * 1e3);
    return status;
}

}  // namespace contactlab::render
