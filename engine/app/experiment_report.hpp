// experiment_report.hpp — `contactlab experiment analyze --report DIR`: the analysis as a Markdown
// page (report.md) with its tables (per condition figures, confusion matrices, t tests) and PNG
// plots rendered by ContactLab's own chart drawer (engine/render/chart.hpp): proportion correct
// against the stimulus per condition, time against the stimulus per condition (seed 000: against
// d), each condition's confusion matrix (render/matrix_chart.hpp), and Cramer's phi against e
// with one line per k (seed 004, when the results have e and k
// columns). Without a Vulkan device the page says so and keeps its tables.
#pragma once

#include "engine/experiments/results_table.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace contactlab::app {

// Writes DIR/report.md and DIR/*.png; returns the page's path.
std::string write_experiment_report(const experiments::ResultsTable& table, const nlohmann::json& analysis,
                                    const std::string& dir);

}  // namespace contactlab::app
