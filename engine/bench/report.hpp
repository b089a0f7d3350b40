// report.hpp — `contactlab bench` output: JSON (the keys issue 8 names: tick_ns.<kind>.<N>) and a
// Markdown page of tables for people.
#pragma once

#include "engine/bench/suites.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace contactlab::bench {

nlohmann::json results_json(const BenchResults& r);
nlohmann::json trace_json(const TraceTiming& t);

// The tables (cost growth with baselines, feature costs, Pareto) as Markdown.
std::string results_markdown(const BenchResults& r);

}  // namespace contactlab::bench
