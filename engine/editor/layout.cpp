// layout.cpp — the editor's fixed layout (layout.hpp).
#include "engine/editor/layout.hpp"

#include "engine/editor/live_plot.hpp"
#include "engine/editor/rulers.hpp"

#include <algorithm>

namespace contactlab::editor {

float plots_panel_height(int plots, float row) {
    constexpr float kPadding = 8.0f, kSpacing = 4.0f;  // px: Dear ImGui's default window padding, item spacing
    return row + 2.0f * kPadding + static_cast<float>(plots) * (kLivePlotHeight + kSpacing) + kTimeAxisHeight + kSpacing;
}

EditorLayout editor_layout(int width, int height, float row, int plots) {
    const float w = static_cast<float>(width), h = static_cast<float>(height);
    EditorLayout l;
    l.menu_bar = {0.0f, 0.0f, w, row};
    l.status_row = {0.0f, l.menu_bar.bottom(), w, row};
    l.top_ruler = {0.0f, l.status_row.bottom(), w, kRulerBand};
    l.message_row = {0.0f, h - row, w, row};
    l.left_ruler = {0.0f, l.top_ruler.bottom(), kLeftRulerWidth, l.message_row.y - l.top_ruler.bottom()};
    l.canvas_top = l.top_ruler.bottom();
    l.canvas_left = kLeftRulerWidth;
    l.canvas_bottom = row;

    const float top = l.top_ruler.bottom() + kPanelGap;
    const float bottom = l.message_row.y - kPanelGap;
    const float avail = std::max(0.0f, bottom - top);
    l.tuning = {l.left_ruler.right() + kPanelGap, top, kTuningWidth, avail};
    const float rx = std::max(l.tuning.right() + kPanelGap, w - kRightColumnWidth - kPanelGap);
    // The Plots panel as tall as its plots (none of them scrolled out of sight), the Haptics panel
    // the rest (its text scrolls; the emergency stop is its first row), at least kMinHapticsHeight.
    const float plots_h = std::clamp(plots_panel_height(plots, row), 0.0f, std::max(0.0f, avail - kMinHapticsHeight - kPanelGap));
    const float haptics_h = std::max(0.0f, avail - plots_h - kPanelGap);
    l.haptics = {rx, top, kRightColumnWidth, haptics_h};
    l.plots = {rx, l.haptics.bottom() + kPanelGap, kRightColumnWidth, plots_h};
    return l;
}

}  // namespace contactlab::editor
