// frame.hpp — the scene drawer: scene + proxy state + view -> draw list. The one drawing path
// shared by offscreen rendering and (next) the window.
//
// Painter's order: grid, anticipation zones (overlay), solids, contours, c-space boundary
// (overlay), proxy ghost, finger, target (and roller) on the pad, force arrow, contacts, anticipation marker, legend.
#pragma once

#include "engine/render/draw_list.hpp"
#include "engine/render/label_place.hpp"
#include "engine/render/theme.hpp"
#include "engine/render/view.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/scene.hpp"

#include <array>
#include <optional>
#include <string>

namespace contactlab::render {

struct Overlays {
    bool cspace = false;  // the c-space obstacle boundary for the finger's phi (seed 000 Fig. 5)
    bool zones = false;   // free space split by the nearest c-space piece's kind (seed 000 Fig. 6)
};

// Seed 003's wearable platform under the pad, in side view (issue 17): where it is relative to
// the pad and what pulls it. Drawn when a frame carries one.
struct PlatformDrawing {
    double roll = 0.0;    // rad, the platform's tilt from the pad's tangent, + fingertip side toward the finger
    double press = 0.0;   // m, how far it is pressed into the pad
    std::array<double, 3> tension{};  // N, cables 1-3 (1 and 2 proximal, 3 distal: Table 2)
    double full_tension = 1.5;        // N: a cable arrow's full length
};

struct FrameContent {
    const Scene* scene = nullptr;
    const Environment* env = nullptr;  // built from *scene
    std::optional<ProxyOutput> finger; // the proxy's state; nothing drawn for the finger if empty
    FingerShape shape;                 // pad R, L
    double max_force = 1.5;            // N: the force arrow's full length
    Overlays overlays;
    // Labels (scale bar, force bar, a status line) drawn with stb_easy_font. Off in golden images.
    bool text = false;
    // The roller's measured position on the pad (m, like l), when a device reports one.
    std::optional<double> roller_l;
    // The wearable platform, when the device is one.
    std::optional<PlatformDrawing> platform;
    // px of each edge covered by something else (the editor's menu bar, status rows and rulers):
    // the status line and the legend keep clear of them. 0 for offscreen pictures.
    float top_inset_px = 0.0f;
    float left_inset_px = 0.0f;
    float bottom_inset_px = 0.0f;
    // px of the right edge covered (the editor's right column of panels): the force-scale bar is
    // drawn left of it, never under the Plots panel.
    float right_inset_px = 0.0f;
    // The proxy's state as a line of text at the top left (with `text`). The editor shows it in
    // a row of its own instead (proxy_status_text).
    bool status_line = true;
};

// Where the legend's bars go (px, top-left origin, their labels included): the length scale bar at
// the bottom left and the force-scale bar (the arrow length of max_force) at the bottom right,
// inside the insets. draw_legend draws exactly these; the editor's layout check reads them.
struct PxBox {
    float x = 0.0f, y = 0.0f, w = 0.0f, h = 0.0f;
};
struct LegendLayout {
    PxBox scale_bar;
    std::optional<PxBox> force_bar;  // with a finger only
    std::optional<PxBox> platform_key;  // with the wearable platform and text: its colours, in the
                                        // first corner that covers no mark (top right first)
    std::optional<PxBox> status_line;   // with text, a finger and status_line: top left, or the
                                        // first free place at the edges; none when none is free
    double scale_bar_m = 0.01;       // m the scale bar stands for
};
LegendLayout legend_layout(const FrameContent& content, const View& view);

// "x_f (1.0, 2.0) mm  phi 0.0 deg  contacts 1  |F| 0.500 N  l_d +0.00 mm": the status line.
std::string proxy_status_text(const ProxyOutput& o);

// Tolerance (px) for flattening curves: chord error at most this.
inline constexpr double kFlattenTolerancePx = 0.2;

// The view that shows the whole scene and the finger (with its body), with a margin.
View default_view(const FrameContent& content, int width, int height);
// The view zoomed on the fingertip: the pad's middle and half the pad radius R around it, where
// seed 003's platform (14 mm), its tension arrows and the contact frame lie (the cables run on,
// out of the picture, to the nail side). The default view of a scene 30 cm wide drew the platform
// a few pixels long. fingertip_box is the part of the world it frames (m); the view needs
// content.finger.
Aabb fingertip_box(Vec2 finger, double phi, double radius);
View fingertip_view(const FrameContent& content, int width, int height);

// Fills `out` (its size is the view's) with the frame: build_scene_layer, then build_overlay_layer.
// `placed`, when given, receives where the overlay's labels went and the marks they avoided.
void build_frame(const FrameContent& content, const View& view, const Theme& theme, DrawList& out,
                 LabelMarks* placed = nullptr);

// The frame in two layers, so that a caller drawing many frames (the editor) can keep the first
// while only the finger moves: drawn in this order into one target they give build_frame's pixels.
// The scene layer is the grid and the solids: it depends on the scene, the view and the theme
// only, except with the zones overlay, which lies between them and follows the finger (see
// scene_layer_follows_finger). The overlay layer is the rest: c-space overlay, proxy ghost,
// finger, force, contacts and the legend. Both append to `out` (build_frame clears it first).
void build_scene_layer(const FrameContent& content, const View& view, const Theme& theme, DrawList& out);
void build_overlay_layer(const FrameContent& content, const View& view, const Theme& theme, DrawList& out,
                         LabelMarks* placed = nullptr);
// True when the scene layer also depends on the finger (the zones overlay is on).
bool scene_layer_follows_finger(const FrameContent& content);

}  // namespace contactlab::render
