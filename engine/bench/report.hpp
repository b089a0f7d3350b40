// report.hpp — `contactlab bench` output: JSON (the keys issue 8 names: tick_ns.<kind>.<N>,
// render_ms.<N>) and a Markdown page of tables, with the report's plots linked, for people.
#pragma once

#include "engine/bench/plots.hpp"
#include "engine/bench/suites.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace contactlab::bench {

nlohmann::json results_json(const BenchResults& r);
nlohmann::json trace_json(const TraceTiming& t);

// `bench --scene --input --ticks OUT.csv`: one row per tick (needs time_trace's rows):
// pass,sample,ns,contact,gather_ns,pieces_ns,walk_ns,contact_ns,anticipate_ns,profiled_ns. `ns` is
// the plain pass's time of the tick; the stages and `profiled_ns` come from the profiled replay of
// the same sample (docs/benchmarks.md, "Your own scene").
std::string ticks_csv(const TraceTiming& t);

// The tables (cost growth with baselines, feature costs, Pareto, stability, roller, frame time)
// as Markdown. With `plots` (the --report folder's PNGs), each figure is linked under its table,
// or the page says why it is missing.
std::string results_markdown(const BenchResults& r, const ReportPlots* plots = nullptr);

}  // namespace contactlab::bench
