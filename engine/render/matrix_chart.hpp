// matrix_chart.hpp — a count matrix as a picture (an experiment's confusion matrix: rows
// stimuli, columns responses): each cell shaded by its share of its row (white 0 to dark blue 1)
// with its count printed, row and column labels and axis titles. Drawn into the one drawing path
// (a DrawList) like the line charts, and rendered offscreen to PNG.
#pragma once

#include "engine/render/context.hpp"
#include "engine/render/draw_list.hpp"

#include <string>
#include <vector>

namespace contactlab::render {

struct MatrixChart {
    std::string title;
    std::string row_title = "stimulus", column_title = "response";
    std::vector<std::string> rows, columns;
    std::vector<std::vector<long>> counts;  // counts[r][c]; rows x columns
    int cell = 56;                          // px per cell side
};

// Picture size (px) for the chart.
P2 matrix_chart_size(const MatrixChart& m);
// Draws into `out` (sized matrix_chart_size). Throws ChartError (chart.hpp) when counts do not
// match the labels.
void draw_matrix_chart(const MatrixChart& m, DrawList& out);
// Renders offscreen on white and writes a PNG (atomically).
void write_matrix_chart_png(const VulkanContext& ctx, const MatrixChart& m, const std::string& path);

}  // namespace contactlab::render
