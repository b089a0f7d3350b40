// layout.hpp — where the editor's fixed parts go in a window of W x H px, so none covers another
// at 1280 x 720 or larger (issue 19 item 3: the proxy's status line used to sit on the rulers'
// labels and the Tuning panel's top). From the top: the menu bar, the status row (the proxy's
// state), the top ruler; the left ruler down the left edge; the message row along the bottom.
// The Tuning panel fills the left column between the rulers and the message row, the Haptics
// and Plots panels share the right column: the Plots panel as tall as its plots need (issue 29:
// every plot in sight at 1280 x 720), the Haptics panel the rest. Panels keep the user's moves after the first frame
// until the window's size changes, and collapse; the canvas is drawn under them.
#pragma once

namespace contactlab::editor {

struct Rect {
    float x = 0.0f, y = 0.0f, w = 0.0f, h = 0.0f;  // px, top-left origin
    float right() const { return x + w; }
    float bottom() const { return y + h; }
};

// Strict overlap (shared edges are not an overlap).
inline bool overlaps(const Rect& a, const Rect& b) {
    return a.x < b.right() && b.x < a.right() && a.y < b.bottom() && b.y < a.bottom();
}

struct EditorLayout {
    Rect menu_bar, status_row, top_ruler, left_ruler, message_row;
    Rect tuning, haptics, plots;
    // px of the canvas edges that the parts above cover (render::FrameContent insets).
    float canvas_top = 0.0f, canvas_left = 0.0f, canvas_bottom = 0.0f;
};

inline constexpr float kLeftRulerWidth = 44.0f;  // px: the left ruler's band (labels in mm)
inline constexpr float kTuningWidth = 372.0f;     // px: the longest Tuning label fits
inline constexpr float kRightColumnWidth = 360.0f;
inline constexpr float kPanelGap = 6.0f;          // px between panels and the fixed parts
inline constexpr float kMinHapticsHeight = 150.0f; // px: the Haptics panel keeps its emergency stop in sight

// px the Plots panel needs for `plots` plots (live_plot.hpp) and the time axis under them.
float plots_panel_height(int plots, float row);

// `row` is ImGui's frame height (px): the menu bar's, and each status row's. `plots`: how many
// plots the Plots panel shows for the device (6 with a roller, 5 without).
EditorLayout editor_layout(int width, int height, float row, int plots = 6);

}  // namespace contactlab::editor
