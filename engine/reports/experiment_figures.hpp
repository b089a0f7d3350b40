// experiment_figures.hpp — the seeds' own figures, drawn from a results file for `experiment
// analyze --report`: what the paper plotted, with the paper's intervals, so a lab can put its
// figure beside the seed's.
//
//   seed 000  failure proportion per block length d, 99 % Wilson intervals; completion time of the
//             successful trials per d, 99 % t intervals (the seed's Fig. 10)
//   seed 002  proportion correct and IT_est per condition, mean of the participants' values with
//             standard errors (Fig. 5a); small-bumps-only against large-bumps-only stimuli (Fig. 6);
//             mean absolute error by number of small bumps (eq. 7, Fig. 8)
//   seed 003  proportion correct per arc height, per task, 95 % Wilson intervals (Fig. 10)
//   seed 004  Cramer's phi against eccentricity e, per total stiffness k (the seed's tables)
//
// Rules every figure keeps: stimuli that are levels or labels sit on a categorical axis with no
// line between them; series at one category are set side by side so none hides another; every
// point says its n; proportions and their intervals stay in [0, 1]; colours are the Okabe-Ito
// palette (colour-blind safe), one per series; no figure of a quantity the protocol fixes (a
// trial's duration in 002-004 is the protocol's, not the participant's).
//
// The experiment is recognised from the results' columns and conditions (seed_of below), so a
// file written by any version of `experiment run` with the seeds' protocols gets its figures.
#pragma once

#include "engine/experiments/base/results_table.hpp"
#include "engine/render/chart.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace contactlab::reports {

struct ReportFigure {
    std::string file;     // PNG file name in the report folder
    render::Chart chart;
    std::string caption;  // printed under the picture: what each point is, n, the interval's rule
};

// A report chart: 900 x 540 px, the title and the axes' titles (with units).
render::Chart report_chart(std::string title, std::string x, std::string y);
// A series of markers with no line between them, palette colour and marker shape by `index`.
render::ChartSeries marker_series(const std::string& name, int index);
// A JSON number printed with `format` (printf) for a report's tables; "-" for null or anything
// not a number (a test with no variance, a fit that did not converge).
std::string report_number(const nlohmann::json& v, const char* format = "%.3g");
// Where series `index` of `count` stands within its category's slot (width 1): they share half.
double dodge(int index, int count);

// Which seed's experiment a results table holds: "000" (conditions force / force+cld, and no
// edge-sharpness `reference_mm` column), "002"
// (conditions F / F+CLD), "003" (a `motion` column), "004" (`e` and `k` columns), or "" for
// none of them.
std::string seed_of(const experiments::ResultsTable& t);

// The seed's figures for the table (none when seed_of is ""). Rows that are warm-up or invalid
// are left out, as the analysis leaves them out.
std::vector<ReportFigure> seed_figures(const experiments::ResultsTable& t);

}  // namespace contactlab::reports
