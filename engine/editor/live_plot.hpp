// live_plot.hpp — one rolling plot of the Plots panel, drawn with Dear ImGui's draw list: a title
// with the unit and the newest value, a y axis with round ticks in that unit, tick marks each
// second along the time axis, and the trace as a min/max envelope per pixel column
// (plot_envelope.hpp), so a one-tick spike shows. One pass over the values per frame, one line
// per column: ~300 lines a plot.
#pragma once

#include "engine/editor/layout.hpp"

#include <vector>

namespace contactlab::editor {

struct LivePlotSpec {
    const char* title;  // "|F|"
    const char* unit;   // "N": shown with the title, the newest value and no tick (ticks are bare numbers)
    float lo, hi;       // the y range; a NaN end follows the data
};

inline constexpr float kLivePlotHeight = 50.0f;  // px of one plot: its title row and its frame
inline constexpr float kTimeAxisHeight = 16.0f;  // px of the time axis's labels under the last plot

// Draws one plot across the window's width and returns its rectangle (screen px). `values`
// (oldest first) span `span_s` seconds up to now, shown at the right of a `window_s` wide axis.
Rect draw_live_plot(const char* id, const std::vector<float>& values, double span_s, double window_s,
                    const LivePlotSpec& spec);
// The time axis's labels (-5 s ... now) under the plots; returns its rectangle.
Rect draw_time_axis(double window_s);

}  // namespace contactlab::editor
