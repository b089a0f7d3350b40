// frame_parts.hpp — the pieces of build_frame (frame.cpp), one file each (internal header).
#pragma once

#include "engine/render/frame.hpp"
#include "engine/render/label_place.hpp"

#include <optional>
#include <vector>

namespace contactlab::render::parts {

// Scale-dependent sizes (px) derived once per frame from the image size.
struct Metrics {
    float contour_width, outline_width, pad_width, dot_radius, arrow_full, arrow_width;
    int text_scale;
};
Metrics metrics_for(const View& view);

// World polyline of a contour's segments in travel order, flattened for the view (px).
void flatten_contour(const Contour& contour, const View& view, std::vector<P2>& out);
// Appends the points of one segment (px); the first point is skipped when `skip_first`.
void flatten_segment(const Segment& segment, const View& view, bool skip_first, std::vector<P2>& out);

void draw_grid(const View& view, const Theme& theme, DrawList& out);                        // frame_grid.cpp
void draw_solids(const Scene& scene, const View& view, const Theme& theme, const Metrics& m,
                 DrawList& out);                                                             // frame_contours.cpp
// The finger body at (center, phi): filled body, outline and highlighted pad (frame_finger.cpp);
// its outline and pad registered in `marks` when given.
void draw_finger_body(Vec2 center, double phi, const FingerShape& shape, const View& view, Color fill,
                      Color outline, Color pad, const Metrics& m, DrawList& out, LabelMarks* marks = nullptr);
// The finger, proxy, contacts, force and platform; every mark registered in `marks`, then their
// labels (with c.text) placed where they cover nothing (label_place.hpp).
void draw_proxy_state(const FrameContent& c, const View& view, const Theme& theme, const Metrics& m,
                      DrawList& out, LabelMarks& marks);                                      // frame_finger.cpp
// The environment's pieces inside `region` (px) added to `marks` as strokes of `width` px.
void add_contour_marks(const Environment& env, const View& view, const LabelBox& region, float width,
                       LabelMarks& marks);                                                   // frame_finger.cpp
void draw_cspace(const FrameContent& c, const View& view, const Theme& theme, const Metrics& m,
                 DrawList& out);                                                             // frame_overlays.cpp
void draw_zones(const FrameContent& c, const View& view, const Theme& theme, DrawList& out); // frame_overlays.cpp
// The legend where `l` (legend_layout, computed once per frame by the caller) puts it.
void draw_legend(const FrameContent& c, const View& view, const Theme& theme, const Metrics& m, const LegendLayout& l,
                 DrawList& out);                                                             // frame_grid.cpp
// The wearable platform's key (cable tension and force colours) in l.platform_key, with the text.
void draw_platform_key(const FrameContent& c, const Theme& theme, const Metrics& m, const LegendLayout& l,
                       DrawList& out);                                                       // frame_grid.cpp

}  // namespace contactlab::render::parts
