// plot_envelope.hpp — what a live plot draws in each pixel column, and its axis ticks (pure, so
// tests see them without a window). ImGui's PlotLines samples one value per column and drops the
// rest: a 1 ms spike among 5 s of servo ticks (5000 values in ~300 columns) vanished. Here each
// column spans the min and max of every value that falls in it (and the last value before it, so
// the trace stays joined), so a single-tick spike always shows.
#pragma once

#include <cstddef>
#include <vector>

namespace contactlab::editor {

struct ColumnRange {
    float lo = 0.0f, hi = 0.0f;
    bool empty = true;  // no value falls in this column (fewer values than columns leave gaps)
};

// `values` oldest first, spread over `columns` columns (the newest at the right edge);
// non-finite values are skipped. O(values + columns).
std::vector<ColumnRange> column_envelope(const std::vector<float>& values, int columns);

// The finite min and max of `values` (0, 1 when there is none; widened to a span of at least
// 1e-6 of their size, so a constant trace gets an axis).
void value_range(const std::vector<float>& values, float& lo, float& hi);

// Round tick values (1, 2 or 5 times a power of ten apart) from lo to hi: at most max_ticks of
// them unless fewer than two round values would fall inside at that spacing (then the next finer
// step), and at least 2 when lo < hi.
std::vector<double> nice_ticks(double lo, double hi, int max_ticks);

}  // namespace contactlab::editor
