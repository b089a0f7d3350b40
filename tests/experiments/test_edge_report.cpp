// test_edge_report.cpp — the README's edge-sharpness commands as a new user runs them, three
// simulated participants: the report says what the data do not bound instead of printing an
// interval from the search's limits, says whether each track converged, reads the fit at the
// staircase's target p, and opens with its limits.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>

using nlohmann::json;
using namespace cli_test;

namespace {
bool starts(const json& j, const std::string& head) { return j.is_string() && j.get<std::string>().rfind(head, 0) == 0; }
}  // namespace

TEST_CASE("edge report: three simulated participants, the force fit's threshold interval is null with its reason") {
    TempDir dir;
    const std::string out = dir.file("redge.csv");
    const auto run = run_contactlab({"experiment", "run", (source_dir() / "scenes/experiments/edge-sharpness.json").string(),
                                     "--participants", "sim:1-3", "--seed", "1", "--jobs", "2", "--no-traces", "-o", out});
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    const auto a = run_contactlab({"experiment", "analyze", out, "--psychometric", "logistic", "--report", dir.file("repedge"), "--json",
                                   dir.file("redge.json")});
    INFO("analyze: " << a.out << a.err);
    REQUIRE(a.exit_code == 0);
    const json j = json::parse(read_text(dir.file("redge.json")));
    const json& f = j["conditions"]["force"]["psychometric"];
    MESSAGE("force fit: ", f.dump());
    // The case: -7,194 .. 3.17 mm before; the data do not bound the lower end.
    CHECK(f["threshold_ci"].is_null());
    CHECK(starts(f["threshold_ci_undefined"], "not bounded by these data"));
    // Every interval reported in either condition is one the data bound: inside the stimuli
    // widened by half their range on each side, with width, around its estimate.
    for (const char* c : {"force", "force+cld"}) {
        const json& g = j["conditions"][c]["psychometric"];
        double lo = 1e300, hi = -1e300;
        for (const auto& b : g["bins"]) lo = std::min(lo, b["x"].get<double>()), hi = std::max(hi, b["x"].get<double>());
        if (g["threshold_ci"].is_array()) {
            CHECK(g["threshold_ci"][0].get<double>() >= lo - 0.5 * (hi - lo));
            CHECK(g["threshold_ci"][1].get<double>() <= hi + 0.5 * (hi - lo));
            CHECK(g["threshold_ci"][0].get<double>() < g["threshold"].get<double>());
            CHECK(g["threshold"].get<double>() < g["threshold_ci"][1].get<double>());
        } else {
            CHECK(starts(g["threshold_ci_undefined"], "not "));
        }
        const json& cmp = j["conditions"][c]["thresholds_compared"];
        CHECK(cmp["staircase_target_p"].get<double>() == doctest::Approx(0.7071).epsilon(1e-3));
        CHECK(cmp.contains("fit_at_target_p"));
        for (const auto& [p, part] : j["conditions"][c]["participants"].items()) CHECK(part["adaptive"]["converged"].is_boolean());
    }
    const std::string md = read_text(dir.file("repedge/report.md"));
    REQUIRE(contains(md, "## Limits"));
    REQUIRE(contains(md, "## Thresholds"));
    CHECK(md.find("## Limits") < md.find("## Thresholds"));
    CHECK(contains(md, "not bounded by these data ("));
    CHECK(contains(md, "Convergence: a staircase track converged when"));
    CHECK(contains(md, "| force | 0.707 | "));  // the same-p table
}
