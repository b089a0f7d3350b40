// test_binary_tests.cpp — the binary-outcome tests (binary_tests.hpp) against an independent
// brute-force enumeration of sign assignments, and their intervals inside [-1, 1] where the
// paired t interval leaves it.
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/analysis/binary_tests.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <string>

using namespace contactlab::experiments;
using namespace cli_test;

namespace {

// Every +-1 vector by recursion (not bit tricks, unlike the code under test): the share whose
// |sum of s_i d_i| reaches the observed |sum d_i|.
double brute_force_p(const std::vector<double>& d) {
    double observed = 0.0;
    for (double v : d) observed += v;
    observed = std::abs(observed);
    long hits = 0, all = 0;
    std::function<void(std::size_t, double)> walk = [&](std::size_t i, double sum) {
        if (i == d.size()) {
            ++all;
            hits += std::abs(sum) >= observed - 1e-12;
            return;
        }
        walk(i + 1, sum + d[i]);
        walk(i + 1, sum - d[i]);
    };
    walk(0, 0.0);
    return static_cast<double>(hits) / static_cast<double>(all);
}

}  // namespace

TEST_CASE("binary tests: the exact sign-flip p equals a brute-force enumeration") {
    const std::vector<std::vector<double>> cases = {
        {0.1, 0.2, 0.3},
        {0.5, -0.1, 0.25, 0.3, 0.05, 0.4},
        {0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2},  // ties: every flip of equal values
        {0.9, -0.8, 0.1, 0.0, 0.3, -0.2, 0.6, 0.15, 0.45, -0.05, 0.35, 0.5},
    };
    for (const auto& d : cases) {
        bool exact = false;
        long assignments = 0;
        const double p = sign_flip_p(d, 1, exact, assignments);
        CHECK(exact);
        CHECK(assignments == (1L << d.size()));
        CHECK(p == doctest::Approx(brute_force_p(d)).epsilon(1e-12));
    }
    // All equal and positive: only "all +" and "all -" reach it, p = 2 / 2^8.
    bool exact = false;
    long n = 0;
    CHECK(sign_flip_p(cases[2], 1, exact, n) == doctest::Approx(2.0 / 256.0));
}

TEST_CASE("binary tests: beyond 20 participants the Monte-Carlo p is within 4 sd of the exact one") {
    std::vector<double> d;
    for (int i = 0; i < 22; ++i) d.push_back(0.05 * ((i * 7) % 11) - 0.2);
    const double truth = brute_force_p(d);
    bool exact = true;
    long draws = 0;
    const double p = sign_flip_p(d, 3, exact, draws);
    CHECK_FALSE(exact);
    CHECK(draws == kMonteCarloDraws);
    const double sd = std::sqrt(truth * (1.0 - truth) / kMonteCarloDraws);
    MESSAGE("exact ", truth, ", Monte Carlo ", p, ", sd ", sd);
    CHECK(std::abs(p - truth) <= 4.0 * sd + 1.0 / kMonteCarloDraws);
}

TEST_CASE("binary tests: failure proportions near 1 get a bootstrap interval inside [-1, 1] where the t interval leaves it") {
    // Ten participants, 10 trials a condition: in A nearly every trial fails, in B almost none.
    std::string csv = "participant,condition,time_s,failed\n";
    const int fail_a[] = {10, 10, 10, 10, 10, 10, 10, 10, 10, 10}, fail_b[] = {0, 0, 0, 0, 0, 0, 0, 0, 7, 0};
    for (int p = 0; p < 10; ++p)
        for (int c = 0; c < 2; ++c)
            for (int j = 0; j < 10; ++j)
                csv += "p" + std::to_string(p) + "," + (c ? "B" : "A") + ",1.0," + (j < (c ? fail_b[p] : fail_a[p]) ? "1" : "0") + "\n";
    const auto r = analyze_results(parse_results_csv(csv, "fail.csv"));
    const nlohmann::json* t = nullptr;
    for (const auto& c : r["comparisons"])
        if (c["measure"] == "failure_proportion") t = &c;
    REQUIRE(t != nullptr);
    CHECK((*t)["ci_high"].get<double>() > 1.0);  // the t interval leaves [-1, 1] here
    const auto& b = (*t)["binary"];
    REQUIRE(b["interval"].is_array());
    CHECK(b["interval"][0].get<double>() >= -1.0);
    CHECK(b["interval"][1].get<double>() <= 1.0);
    CHECK(b["interval"][0].get<double>() <= b["mean_difference"].get<double>());
    CHECK(b["mean_difference"].get<double>() == doctest::Approx((*t)["mean_difference"].get<double>()));
    // d: nine 1s and one 0.3 (mean 0.93, sd 0.22: t interval 0.77 .. 1.09); flipping any one
    // lowers |sum| below 9.3, so only "all +" and "all -" reach it: p = 2 / 1024.
    CHECK(b["permutation"]["p"].get<double>() == doctest::Approx(brute_force_p({1, 1, 1, 1, 1, 1, 1, 1, 0.3, 1})));
    CHECK(b["permutation"]["p"].get<double>() == doctest::Approx(2.0 / 1024.0));
    CHECK(b["rule"].get<std::string>().find("permutation") != std::string::npos);
}

TEST_CASE("binary tests: seed 000's failures in the report, the permutation test and bootstrap beside the t test") {
    TempDir dir;
    std::string csv = "participant,condition,block_d_cm,time_s,failed\n";
    const int fail_a[] = {6, 5, 7, 4, 6, 5}, fail_b[] = {2, 1, 3, 2, 0, 2};
    for (int p = 0; p < 6; ++p)
        for (int c = 0; c < 2; ++c)
            for (int j = 0; j < 8; ++j)
                csv += "p" + std::to_string(p) + "," + (c ? "force+cld" : "force") + ",4,2.5," + (j < (c ? fail_b[p] : fail_a[p]) ? "1" : "0") + "\n";
    write_text(dir.file("s0.csv"), csv);
    const auto r = run_contactlab({"experiment", "analyze", dir.file("s0.csv"), "--report", dir.file("rep")});
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const std::string md = read_text(dir.file("rep/report.md"));
    CHECK(md.find("Binary outcomes: for binary outcomes, beside the t test") != std::string::npos);
    // d = (6-2)/8, (5-1)/8, ... all positive: only "all +" and "all -" of 64 reach the sum.
    CHECK(md.find("permutation p = 0.0312 (exact, 64)") != std::string::npos);
    CHECK(md.find("% bootstrap interval ") != std::string::npos);
    CHECK(md.find("## Limits") < md.find("## Comparisons"));
}

TEST_CASE("binary tests: three participants get a permutation p but no bootstrap interval, with the reason") {
    std::vector<BinaryPair> pairs = {{9, 10, 2, 10}, {8, 10, 3, 10}, {10, 10, 1, 10}};
    const BinaryComparison c = compare_binary(pairs);
    CHECK(c.undefined.empty());
    CHECK(c.p == doctest::Approx(0.25));  // 2 of 8 sign assignments reach the observed sum
    CHECK(c.min_p == doctest::Approx(0.25));
    CHECK(c.ci_undefined.find("not reported: 3 participants, 5 needed") == 0);
}
