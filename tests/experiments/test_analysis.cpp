// test_analysis.cpp — `experiment analyze` on results tables whose figures are known by hand:
// seed 004's Table I written out as 100 trials, exclusions of warm-up and invalid rows, per
// participant figures and their means, and the t tests between two conditions.
#include "engine/experiments/analysis/analysis.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>

using namespace contactlab::experiments;
using nlohmann::json;

namespace {

// Table I: stimulus 45 (F1) or 135 (F2) deg, response A or B; 41 / 9 and 3 / 47. Ten warm-up
// rows and five invalid rows are added, all answered wrong, to show that they are left out.
std::string table_one_csv() {
    std::ostringstream s;
    s << "participant,condition,trial,stimulus,response,correct,valid,warmup\n";
    int trial = 0;
    auto rows = [&](const char* stim, const char* resp, int n, int correct, int valid, int warmup) {
        for (int i = 0; i < n; ++i, ++trial)
            s << "p" << (trial % 5) << ",e0.40 k0.75," << trial << "," << stim << "," << resp << "," << correct << ","
              << valid << "," << warmup << "\n";
    };
    rows("45", "A", 41, 1, 1, 0);
    rows("45", "B", 9, 0, 1, 0);
    rows("135", "A", 3, 0, 1, 0);
    rows("135", "B", 47, 1, 1, 0);
    rows("45", "B", 10, 0, 1, 1);
    rows("135", "A", 5, 0, 0, 0);
    return s.str();
}

}  // namespace

TEST_CASE("analyze: seed 004 Table I as trials gives phi 0.766 with warm-up and invalid rows left out") {
    const json r = analyze_results(parse_results_csv(table_one_csv(), "table1.csv"));
    CHECK(r["rows"] == 115);
    CHECK(r["excluded"] == 15);
    const json& c = r["conditions"]["e0.40 k0.75"];
    CHECK(c["n"] == 100);
    CHECK(c["cramers_phi"].get<double>() == doctest::Approx(0.765532).epsilon(1e-6));
    CHECK(c["proportion_correct"].get<double>() == doctest::Approx(0.88));
    CHECK(c["labels"]["stimuli"] == json::array({"45", "135"}));
    CHECK(c["labels"]["responses"] == json::array({"A", "B"}));
    CHECK(c["confusion"] == json::array({json::array({41, 9}), json::array({3, 47})}));
    CHECK(c["per_stimulus"]["45"]["proportion_correct"].get<double>() == doctest::Approx(41.0 / 50.0));
    CHECK(c["participants"].size() == 5);
    CHECK(r["comparisons"].empty());  // one condition: nothing to compare
}

TEST_CASE("analyze: no condition column is one condition called all, every row counts without valid and warmup") {
    const json r = analyze_results(parse_results_csv("stimulus,response\n1,1\n2,2\n2,1\n1,1\n", "plain.csv"));
    CHECK(r["excluded"] == 0);
    const json& c = r["conditions"]["all"];
    CHECK(c["n"] == 4);
    CHECK(c["proportion_correct"].get<double>() == doctest::Approx(0.75));
    // IT_est: n = 4, rows 2, 2, columns 3, 1: 0.5 log2(2 4 / 6) + 0.25 log2(1 4 / 6) + 0.25 log2(1 4 / 2).
    const double it = 0.5 * std::log2(8.0 / 6.0) + 0.25 * std::log2(4.0 / 6.0) + 0.25 * std::log2(2.0);
    CHECK(c["it_est_bits"].get<double>() == doctest::Approx(it).epsilon(1e-12));
}

TEST_CASE("analyze: two conditions with several participants are compared by paired t tests") {
    // Two participants, two conditions, timed trials (seed 000's shape): per participant mean
    // times of successful trials F: 4 and 6 s, F+CLD: 2 and 3 s -> differences 2 and 3, mean 2.5,
    // sd 0.7071, t = 5 on 1 df. Failures: F 1 of 3 per participant, F+CLD none.
    const std::string csv =
        "participant,condition,trial,stimulus,response,time_s,failed\n"
        "a,force,1,0.06,,4,0\na,force,2,0.06,,4,0\na,force,3,0.06,,9,1\n"
        "b,force,1,0.06,,6,0\nb,force,2,0.06,,6,0\nb,force,3,0.06,,1,1\n"
        "a,force+cld,1,0.06,,2,0\na,force+cld,2,0.06,,2,0\na,force+cld,3,0.06,,2,0\n"
        "b,force+cld,1,0.06,,3,0\nb,force+cld,2,0.06,,3,0\nb,force+cld,3,0.06,,3,0\n";
    const json r = analyze_results(parse_results_csv(csv, "timed.csv"));
    const json& f = r["conditions"]["force"];
    CHECK(f["time_s"]["mean"].get<double>() == doctest::Approx(5.0));  // 4 4 6 6, the failures left out
    CHECK(f["failure_proportion"].get<double>() == doctest::Approx(2.0 / 6.0));
    CHECK(f["participant_means"]["time_s"].get<double>() == doctest::Approx(5.0));
    CHECK_FALSE(f.contains("proportion_correct"));  // no answers in a timed task
    REQUIRE(r["comparisons"].size() == 2);
    const json& time = r["comparisons"][0];
    CHECK(time["measure"] == "time_s");
    CHECK(time["paired"] == true);
    CHECK(time["a"] == "force");
    CHECK(time["mean_difference"].get<double>() == doctest::Approx(2.5));
    CHECK(time["t"].get<double>() == doctest::Approx(5.0));
    CHECK(time["df"].get<double>() == 1.0);
    // Failures: per participant 1/3 against 0, no variance in the differences: no valid test.
    CHECK(r["comparisons"][1]["measure"] == "failure_proportion");
    CHECK(r["comparisons"][1]["valid"] == false);
}

TEST_CASE("analyze: a bad results file names the line and column") {
    CHECK_THROWS_WITH_AS(parse_results_csv("stimulus,response\n1,2,3\n", "bad.csv"),
                         "bad.csv: line 2: 3 fields, the header has 2", ExperimentError);
    CHECK_THROWS_WITH_AS(analyze_results(parse_results_csv("stimulus,response,valid\n1,1,yes\n", "v.csv")),
                         "v.csv: line 2, column valid: expected a number, found \"yes\"", ExperimentError);
    CHECK_THROWS_AS(parse_results_csv("", "empty.csv"), ExperimentError);
    CHECK_THROWS_AS(parse_results_csv("a,a\n1,2\n", "twice.csv"), ExperimentError);
    CHECK_THROWS_AS(parse_results_csv("a,b\n\"1,2\n", "quote.csv"), ExperimentError);
}

TEST_CASE("analyze: the movement's measures, contact share and breaks, per condition and per stimulus with t intervals") {
    // Two participants, two conditions, two block lengths. Force: contact shares 0.9, 0.7 (d 0.04)
    // and 0.8, 0.6 (d 0.06), breaks 1, 3, 2, 2; force+cld: shares 1, 1, 0.9, 0.9, breaks 0, 0, 1, 1.
    // Failed trials count: a broken contact is part of how the finger moved.
    const std::string csv =
        "participant,condition,trial,stimulus,response,time_s,failed,contact_breaks,contact_fraction\n"
        "a,force,1,0.04,,4,0,1,0.9\nb,force,1,0.04,,,1,3,0.7\n"
        "a,force,2,0.06,,5,0,2,0.8\nb,force,2,0.06,,,1,2,0.6\n"
        "a,force+cld,1,0.04,,2,0,0,1\nb,force+cld,1,0.04,,3,0,0,1\n"
        "a,force+cld,2,0.06,,2,0,1,0.9\nb,force+cld,2,0.06,,3,0,1,0.9\n";
    const json r = analyze_results(parse_results_csv(csv, "moves.csv"), AnalyzeOptions{0.95});
    const json& f = r["conditions"]["force"];
    CHECK(f["contact_fraction"]["n"] == 4);
    CHECK(f["contact_fraction"]["mean"].get<double>() == doctest::Approx(0.75));
    // sd of 0.9 0.7 0.8 0.6 = sqrt(0.05 / 3); t(3) at 0.975 = 3.182446
    const double sd = std::sqrt(0.05 / 3.0), half = 3.182446 * sd / 2.0;
    CHECK(f["contact_fraction"]["sd"].get<double>() == doctest::Approx(sd).epsilon(1e-9));
    CHECK(f["contact_fraction"]["ci_low"].get<double>() == doctest::Approx(0.75 - half).epsilon(1e-6));
    CHECK(f["contact_fraction"]["ci_high"].get<double>() == doctest::Approx(0.75 + half).epsilon(1e-6));
    CHECK(f["contact_breaks"]["mean"].get<double>() == doctest::Approx(2.0));
    // Per block length (seed 000's d): 0.04 has 0.9 and 0.7.
    CHECK(f["per_stimulus"]["0.04"]["contact_fraction"]["mean"].get<double>() == doctest::Approx(0.8));
    CHECK(f["per_stimulus"]["0.06"]["contact_breaks"]["mean"].get<double>() == doctest::Approx(2.0));
    // The time of the successful trials gets its interval too (one here: no interval).
    CHECK(f["per_stimulus"]["0.04"]["time_s"]["ci_low"].is_null());
    CHECK(r["conditions"]["force+cld"]["time_s"]["ci_low"].is_number());
    // Participant means: a 0.85 and 0.65 -> 0.75.
    CHECK(f["participant_means"]["contact_fraction"].get<double>() == doctest::Approx(0.75));
    // Paired comparisons of both measures follow time and failures.
    bool share = false, breaks = false;
    for (const json& c : r["comparisons"]) {
        if (c["measure"] == "contact_fraction") {
            share = true;
            CHECK(c["paired"] == true);
            CHECK(c["mean_difference"].get<double>() == doctest::Approx(-0.2));  // a: 0.85 - 0.95, b: 0.65 - 0.95
        }
        breaks |= c["measure"] == "contact_breaks";
    }
    CHECK(share);
    CHECK(breaks);
}

TEST_CASE("analyze: a results file from before the movement's measures reads as before, without them") {
    const std::string csv = "participant,condition,trial,stimulus,response,time_s,failed,contact_breaks\n"
                            "a,force,1,0.04,,4,0,0\nb,force,1,0.04,,5,0,1\n";
    const json r = analyze_results(parse_results_csv(csv, "old.csv"));
    CHECK_FALSE(r["conditions"]["force"].contains("contact_fraction"));
    CHECK(r["conditions"]["force"]["contact_breaks"]["mean"].get<double>() == doctest::Approx(0.5));
    CHECK(r["conditions"]["force"]["time_s"]["mean"].get<double>() == doctest::Approx(4.5));
}
