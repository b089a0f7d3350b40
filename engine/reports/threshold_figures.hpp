// threshold_figures.hpp — the report's thresholds (`experiment analyze --report` with
// adaptive results or `--psychometric`): a Markdown table of each condition's adaptive
// estimate and fitted threshold with its interval, and figures: per condition the fitted
// psychometric curve over the binned data (each bin's proportion correct with its 95 % Wilson
// interval and n; the threshold and its bootstrap interval as vertical lines), and each
// participant's staircase or QUEST+ track (stimulus per trial, reversals marked).
#pragma once

#include "engine/reports/experiment_figures.hpp"

#include <nlohmann/json_fwd.hpp>

#include <sstream>
#include <vector>

namespace contactlab::reports {

// The "Thresholds" section of report.md (nothing when the analysis has no thresholds).
void threshold_section(std::ostringstream& md, const nlohmann::json& analysis);
std::vector<ReportFigure> threshold_figures(const nlohmann::json& analysis);

}  // namespace contactlab::reports
