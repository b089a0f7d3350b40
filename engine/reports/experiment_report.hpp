// experiment_report.hpp — `contactlab experiment analyze --report DIR`: the analysis as a Markdown
// page (report.md) with its tables (per condition figures, confusion matrices, t tests) and PNG
// plots rendered by ContactLab's own chart drawer (engine/render/chart.hpp): the seed's own
// figures when the results are one of the seeds' experiments (experiment_figures.hpp), else
// proportion correct per stimulus and condition; each condition's confusion matrix
// (render/matrix_chart.hpp). Every figure has a caption saying what a point is, its n and its
// interval. Without a Vulkan device the page says so and keeps its tables.
//
// Room engine/reports/: the figures and Markdown reports drawn from experiments' results (here,
// experiment_figures.hpp, threshold_figures.hpp, power_report.hpp). Includes engine/experiments/,
// engine/render/ and haptics/; engine/app/ calls it.
#pragma once

#include "engine/experiments/base/results_table.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace contactlab::reports {

// Writes DIR/report.md and DIR/*.png; returns the page's path.
std::string write_experiment_report(const experiments::ResultsTable& table, const nlohmann::json& analysis,
                                    const std::string& dir);

}  // namespace contactlab::reports
