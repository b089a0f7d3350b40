// test_adaptive_convergence.cpp — an adaptive run says what it found (threshold_analysis.hpp):
// per participant whether the track converged by kConvergenceRule, and a few reversals are
// not judged converged.
#include "engine/experiments/analysis/threshold_analysis.hpp"
#include "engine/experiments/base/results_table.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

using namespace contactlab::experiments;
using nlohmann::json;

TEST_CASE("adaptive tracks: one turning between two levels converged, one still drifting down did not, one too short is not judged converged") {
    std::string csv = "participant,condition,stimulus,correct,procedure,target_p,reversal,estimate\n";
    auto row = [&](const char* p, double x, bool reversal) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%s,A,%.4f,1,staircase 1-up-2-down,0.7071,%d,%.4f\n", p, x, reversal ? 1 : 0, x);
        csv += buf;
    };
    // Turning between 2.0 and 2.25 (one final step of 0.25): the last 6 reversals span 1 step.
    for (int i = 0; i < 20; ++i) row("steady", 2.0 + 0.25 * (i % 2), i > 0);
    // Falling 0.25 a trial, a "reversal" marked every other trial: the last 6 span 2.5 = 10 steps.
    for (int i = 0; i < 20; ++i) row("drifting", 4.0 - 0.25 * i, i >= 3 && i % 2 == 1);
    // Three reversals only.
    for (int i = 0; i < 6; ++i) row("short", 2.0 + 0.25 * (i % 2), i >= 3);
    json r;
    add_threshold_analysis(r, parse_results_csv(csv, "tracks.csv"), {});
    const json& parts = r["conditions"]["A"]["participants"];
    CHECK(parts["steady"]["adaptive"]["converged"] == true);
    CHECK(parts["steady"]["adaptive"]["reversal_spread"].get<double>() == doctest::Approx(0.25));
    CHECK(parts["steady"]["adaptive"]["final_step"].get<double>() == doctest::Approx(0.25));
    CHECK(parts["drifting"]["adaptive"]["converged"] == false);
    CHECK(parts["drifting"]["adaptive"]["reversal_spread"].get<double>() == doctest::Approx(2.5));
    CHECK(parts["short"]["adaptive"]["converged"] == false);
    CHECK(parts["short"]["adaptive"]["convergence"].get<std::string>().find("3 reversals, 6 needed") != std::string::npos);
    const json& ad = r["conditions"]["A"]["adaptive"];
    CHECK(ad["converged"] == 1);
    CHECK(ad["judged"] == 3);
    CHECK(ad["convergence_rule"].get<std::string>().find("last 6 reversals") != std::string::npos);
}
