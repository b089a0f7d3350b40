// chart.hpp — line charts for reports (`contactlab bench --report`), drawn into the one drawing
// path (a DrawList) and rendered offscreen like any frame, so ContactLab plots its own figures
// with no plotting library.
//
// A chart: a title, an x and a y axis (linear or log10, a title with units, ticks with labels; or
// categorical: one labelled slot per category), named series (polylines with markers, optionally
// dashed, or markers alone; optional per-point labels and error bars), a legend right of the plot,
// and reference lines at a constant x or y (a budget, a reference mode).
//
// Bad data never crashes: a point with a non-finite coordinate, or a non-positive one on a log
// axis, is skipped (the polyline breaks there) and counted; a chart with nothing to set its range
// from, or with an impossible range, throws ChartError with a message naming the chart and axis.
#pragma once

#include "engine/render/draw_list.hpp"

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace contactlab::render {

struct ChartError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

enum class AxisScale { linear, log10 };

struct ChartAxis {
    std::string title;  // with units, e.g. "ns per tick"
    AxisScale scale = AxisScale::linear;
    // Data range shown. Empty: from the data (log axes widen to whole decades, linear ones to
    // the tick step, and a linear range includes 0 when `include_zero`).
    std::optional<double> min, max;
    bool include_zero = false;
    // Categorical axis: when not empty, category i sits at the value i (0, 1, ...), the axis spans
    // [-0.5, n - 0.5] and its ticks are the categories' names. For stimuli that are labels or a
    // handful of levels (0..4 bumps, 45 / 135 deg): a reader must not read between them.
    std::vector<std::string> categories;
};

enum class Marker { none, disc, square, triangle, diamond };

struct ChartSeries {
    std::string name;  // legend entry
    std::vector<double> x, y;  // same length; units of the axes
    Color color;
    Marker marker = Marker::disc;
    bool dashed = false;
    float line_width = 2.0f;  // px
    std::vector<std::string> labels;  // optional, one per point (empty strings allowed)
    // Optional error bars, one low and one high value per point (units of the y axis; NaN: no bar
    // at that point). Drawn as a vertical line with caps; the y range includes them.
    std::vector<double> y_low, y_high;
    // false: markers (and bars) only, no line between points: categories, or levels where a
    // line would claim values between them.
    bool connect = true;
};

// A straight line across the whole plot at x = value (vertical) or y = value (horizontal).
struct ChartReference {
    std::string label;  // drawn beside the line, and in the legend
    bool vertical = false;
    double value = 0.0;
    Color color{90, 90, 90, 255};
};

struct Chart {
    std::string title;
    ChartAxis x, y;
    std::vector<ChartSeries> series;
    std::vector<ChartReference> references;
    int width = 960, height = 600;  // px
};

// Data -> pixel along one axis: value `lo` lands at `px_lo`, `hi` at `px_hi` (px_hi < px_lo for
// the y axis, pixel y grows downwards); linear in the value, or in log10 of it.
struct AxisMap {
    AxisScale scale = AxisScale::linear;
    double lo = 0.0, hi = 1.0;  // data range (both > 0 on a log axis)
    double px_lo = 0.0, px_hi = 1.0;
    double to_px(double v) const;
    // The value is drawable on this axis (finite; positive on a log axis).
    bool accepts(double v) const;
};

struct ChartTick {
    double value = 0.0;
    std::string label;  // empty for minor ticks
};

// The ticks an axis shows: its categories at 0..n-1 when it has them, else axis_ticks(map).
std::vector<ChartTick> axis_ticks(const ChartAxis& axis, const AxisMap& map);

// Tick positions within [map.lo, map.hi]: linear 1/2/5 x 10^k steps (about 5 to 10 ticks); log:
// every decade labelled, with minor ticks at 2..9 x 10^k when the range spans at most 6 decades,
// and labels at 2 and 5 x 10^k too when it spans at most 2.
std::vector<ChartTick> axis_ticks(const AxisMap& map);
// A tick label: "0", "0.5", "200", "20000", "1e4", "1e-6" (short, ASCII).
std::string tick_label(double v);

// An axis-aligned rectangle in px (lo: top-left, hi: bottom-right).
struct ChartBox {
    P2 lo, hi;
    bool intersects(const ChartBox& o) const { return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y; }
};

// Where everything goes: the plot rectangle (px) and both axis maps; after draw_chart also
// where it put every piece of text and every data mark, so that a test can check that no text
// sits on text or on data.
struct ChartLayout {
    P2 plot_lo, plot_hi;  // top-left and bottom-right of the plot area, px
    AxisMap x, y;
    int skipped_points = 0;  // points left out: non-finite, or non-positive on a log axis
    std::vector<ChartBox> text_boxes;  // every glyph drawn (titles, ticks, legend, labels)
    std::vector<ChartBox> mark_boxes;  // every marker and error bar drawn
    // Point labels (and reference lines' in-plot labels) left out because every place tried
    // beside their point overlapped other text or data; the caller says their values elsewhere.
    int dropped_labels = 0;
    int placed_labels = 0;  // point and reference labels drawn in the plot
};

// Throws ChartError when the size is too small, a series' x and y (or labels) differ in length,
// or an axis has no range (no drawable point and no explicit min/max, min >= max, or a
// non-positive limit on a log axis).
ChartLayout layout_chart(const Chart& chart);

// Draws the chart into `out` (its size must be the chart's; white background assumed: the
// colours are chosen for it). Returns the layout used, with the boxes of what it drew.
// Labels are placed, never stacked: a point's label goes above-right of it, else above-left,
// below-right, below-left, whichever first overlaps no text, marker or error bar and stays in
// the plot; a reference line's label goes beside the line at the top of the plot, right or left,
// a row lower each time, else it stays in the legend only. A label with no free place is left
// out and counted (dropped_labels), in series order: the earlier points keep theirs.
ChartLayout draw_chart(const Chart& chart, DrawList& out);

// Distinguishable series colours for a white background (Okabe-Ito, colour-blind safe), by index.
Color chart_color(int index);

}  // namespace contactlab::render
