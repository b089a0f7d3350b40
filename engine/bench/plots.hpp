// plots.hpp — the figures of `contactlab bench --report DIR`, drawn by ContactLab's own renderer
// (engine/render/chart.hpp) from the same results as the tables:
//   cost_extent.png, cost_dense.png  log-log ns per tick against segments, lines/arcs/curves, with
//                                    the brute-force and point-finger baselines
//   tail_dense.png                   log-log p99.9 and max per tick against segments on the dense
//                                    contours, in contact and hovering, against 100 us and 1 ms
//   pareto.png                       error against ns per tick for the curve modes
//   stability.png                    largest stable Ke against servo rate, next to 2b/T
//   zwidth.png                       largest stable K against virtual damping B (Z-width), pressed
//                                    and sliding, 1 and 10 kHz, next to 2 (b - |B|) / T
//   roller_tracking.png              roller error against finger speed, per pole scale
//   render_frame.png                 offscreen frame time against segments
#pragma once

#include "engine/bench/suites.hpp"
#include "engine/render/chart.hpp"

#include <string>
#include <vector>

namespace contactlab::bench {

inline constexpr int kPlotWidth = 1000, kPlotHeight = 600;  // px, every report plot

struct ReportChart {
    std::string file;  // name inside the report folder, e.g. "pareto.png"
    render::Chart chart;
};

// The charts for these results (no Vulkan involved): one per figure above, leaving out a figure
// whose table is empty (e.g. the frame-time suite when it was skipped).
std::vector<ReportChart> report_charts(const BenchResults& r);

struct PlotFile {
    std::string file, title;
    std::string error;  // why this plot was not written (bad data, render failure); empty if written
    int skipped_points = 0;  // NaN or non-positive-on-log points left out of the figure
};

struct ReportPlots {
    std::string skipped;  // why no plot was written at all (no Vulkan device); empty otherwise
    std::vector<PlotFile> files;
    const PlotFile* find(const std::string& file) const;
};

// Renders every chart offscreen and writes DIR/<file>. Never throws for a missing Vulkan device or
// a chart that cannot be drawn: the reasons are returned for the Markdown to state.
ReportPlots write_report_plots(const BenchResults& r, const std::string& dir);

}  // namespace contactlab::bench
