// power_report.hpp — `contactlab experiment power --report DIR`: the power analysis
// (engine/experiments/analysis/power_analysis.hpp) as a Markdown page (report.md: the test, the
// pool's effect, power per group size with its Wilson interval) and power.png, power against
// group size with alpha and 0.8 marked. Without a Vulkan device the page says so and keeps its
// table.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace contactlab::reports {

// Writes DIR/report.md and DIR/power.png from `experiment power`'s JSON result.
void write_power_report(const nlohmann::json& result, const std::string& dir);

}  // namespace contactlab::reports
