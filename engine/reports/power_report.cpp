// power_report.cpp — `experiment power --report DIR` (power_report.hpp).
#include "engine/reports/power_report.hpp"

#include "engine/reports/experiment_figures.hpp"
#include "engine/render/chart_image.hpp"
#include "engine/render/context.hpp"
#include "haptics/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>

namespace contactlab::reports {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Power against group size with the Wilson intervals, alpha and 0.8 (the usual target) marked.
render::Chart power_chart(const json& r) {
    render::Chart c = report_chart("Power of the paired t test on " + r["measure"].get<std::string>() + " (" +
                                       r["conditions"][0].get<std::string>() + " vs " + r["conditions"][1].get<std::string>() + ")",
                                   "participants per group", "power (share of groups with p < alpha)");
    c.y.min = 0.0;
    c.y.max = 1.0;
    render::ChartSeries s = marker_series("power, 95 % Wilson", 0);
    // Group sizes are counts: one category each, no fractional ticks between them.
    for (const auto& p : r["points"]) {
        c.x.categories.push_back(std::to_string(p["participants"].get<int>()));
        s.x.push_back(static_cast<double>(s.x.size()));
        s.y.push_back(p["power"].get<double>());
        s.y_low.push_back(p["power_ci"][0].get<double>());
        s.y_high.push_back(p["power_ci"][1].get<double>());
    }
    c.series.push_back(s);
    c.references.push_back({"0.8 (a usual target)", false, 0.8});
    c.references.push_back({"alpha " + render::tick_label(r["alpha"].get<double>()), false, r["alpha"].get<double>()});
    return c;
}

}  // namespace

void write_power_report(const json& r, const std::string& dir) {
    fs::create_directories(dir);
    std::ostringstream md;
    md << "# Power: " << r["measure"].get<std::string>() << "\n\n"
       << "- test: " << r["test"].get<std::string>() << "\n- sampling: " << r["sampling"].get<std::string>()
       << "\n- pool: " << r["pool"] << " participants; effect in the pool: mean difference "
       << report_number(r["pool_effect"]["mean_difference"], "%.4g") << ", sd " << report_number(r["pool_effect"]["sd_difference"], "%.4g") << ", d_z "
       << report_number(r["pool_effect"]["dz"], "%.4g") << "\n- alpha " << r["alpha"] << ", seed " << r["seed"] << "\n\n"
       << "| participants | power | 95 % interval | undefined tests | median p |\n| ---: | ---: | --- | ---: | ---: |\n";
    for (const auto& p : r["points"]) {
        char line[160];
        std::snprintf(line, sizeof line, "| %d | %.3f | %.3f .. %.3f | %ld | %s |\n", p["participants"].get<int>(), p["power"].get<double>(),
                      p["power_ci"][0].get<double>(), p["power_ci"][1].get<double>(), p["undefined"].get<long>(),
                      report_number(p["median_p"], "%.4g").c_str());
        md << line;
    }
    try {
        const render::VulkanContext ctx(render::ContextOptions{});
        render::write_chart_png(ctx, power_chart(r), (fs::path(dir) / "power.png").string());
        md << "\n![power](power.png)\n\nEach point: the share of resampled groups of that size whose paired t test had p < alpha, "
              "with its 95 % Wilson interval over the groups (Monte Carlo error only).\n";
    } catch (const std::exception& e) {
        md << "\n(no plot: " << e.what() << ")\n";
    }
    write_file_atomically((fs::path(dir) / "report.md").string(), md.str());
}

}  // namespace contactlab::reports
