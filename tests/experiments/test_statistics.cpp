// test_statistics.cpp — the seeds' statistics against values computed by hand (and, for the t
// distribution's tails, by numerically integrating its density in an independent script):
// seed 004's Table I, information transfer of known matrices, t tests of small samples.
#include "engine/experiments/analysis/statistics.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace contactlab::experiments;

namespace {

// A confusion matrix from counts: stimuli and responses labelled "0", "1", ...
Confusion from_counts(const std::vector<std::vector<long>>& counts) {
    std::vector<std::string> s, r;
    for (std::size_t i = 0; i < counts.size(); ++i)
        for (std::size_t j = 0; j < counts[i].size(); ++j)
            for (long k = 0; k < counts[i][j]; ++k) {
                s.push_back(std::to_string(i));
                r.push_back(std::to_string(j));
            }
    return make_confusion(s, r);
}

}  // namespace

TEST_CASE("statistics: seed 004 Table I gives Cramer's phi 0.766 and a chi-square far beyond chance") {
    // k = 0.75 N/mm, e = 0.40, Experiment I: rows F1 (45 deg), F2 (135 deg); columns SA, SB.
    const Confusion c = from_counts({{41, 9}, {3, 47}});
    REQUIRE(c.total() == 100);
    // Expected counts 22, 28, 22, 28 (row sums 50, 50; column sums 44, 56): X^2 = 2 (19^2/22 +
    // 19^2/28) = 58.6039, phi = sqrt(X^2 / 100) = 0.76553.
    const ChiSquare x = chi_square(c);
    CHECK(x.statistic == doctest::Approx(58.603896).epsilon(1e-7));
    CHECK(x.df == 1.0);
    CHECK(x.p == doctest::Approx(1.92834e-14).epsilon(1e-4));  // erfc(sqrt(X^2 / 2)) for one df
    CHECK(cramers_phi(c) == doctest::Approx(0.765532).epsilon(1e-6));
    CHECK(proportion_correct(c) == doctest::Approx(0.88));
    // IT_est by eq. 6 term by term: 0.41 log2(4100/2200) + 0.09 log2(900/2800) + 0.03 log2(300/2200)
    // + 0.47 log2(4700/2800) = 0.485827 bits.
    CHECK(it_est_bits(c) == doctest::Approx(0.4858265388).epsilon(1e-9));
}

TEST_CASE("statistics: information transfer is log2 K for perfect identification and 0 for none") {
    // Seed 002: five alternatives, 25 presentations each, all answered right: 2.32 bits, the
    // maximum the seed quotes.
    std::vector<std::vector<long>> perfect(5, std::vector<long>(5, 0));
    for (int i = 0; i < 5; ++i) perfect[i][i] = 25;
    CHECK(it_est_bits(from_counts(perfect)) == doctest::Approx(std::log2(5.0)).epsilon(1e-12));
    CHECK(proportion_correct(from_counts(perfect)) == 1.0);
    CHECK(cramers_phi(from_counts(perfect)) == doctest::Approx(1.0).epsilon(1e-12));
    // Responses independent of the stimulus: every cell 5.
    const Confusion flat = from_counts(std::vector<std::vector<long>>(5, std::vector<long>(5, 5)));
    CHECK(it_est_bits(flat) == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(cramers_phi(flat) == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(proportion_correct(flat) == doctest::Approx(0.2));
    // One response for everything: no information, phi undefined and reported as 0.
    const Confusion one = from_counts({{10, 0}, {10, 0}});
    CHECK(it_est_bits(one) == 0.0);
    CHECK(cramers_phi(one) == 0.0);
}

TEST_CASE("statistics: labels sort as numbers and a response never given still counts as wrong") {
    const Confusion c = make_confusion({"10", "2", "30", "2"}, {"10", "3", "30", "2"});
    CHECK(c.stimuli == std::vector<std::string>{"2", "10", "30"});
    CHECK(c.responses == std::vector<std::string>{"2", "3", "10", "30"});
    CHECK(c.counts[0][0] == 1);  // 2 -> 2
    CHECK(c.counts[0][1] == 1);  // 2 -> 3
    CHECK(proportion_correct(c) == doctest::Approx(0.75));
    CHECK_THROWS(make_confusion({"1"}, {}));
}

TEST_CASE("statistics: t tests match hand values, their intervals use the t quantile") {
    // Paired: differences 1..5: mean 3, sd sqrt(2.5), se 0.707107, t = 4.242641 on 4 df; the 95 %
    // quantile of t(4) is 2.776445, so the interval is 3 -+ 1.963243; p = 0.0132356.
    const TTest p = paired_t_test({2, 4, 6, 8, 10}, {1, 2, 3, 4, 5});
    REQUIRE(p.valid);
    CHECK(p.paired);
    CHECK(p.mean_difference == doctest::Approx(3.0));
    CHECK(p.t == doctest::Approx(4.2426407).epsilon(1e-7));
    CHECK(p.df == 4.0);
    CHECK(p.p == doctest::Approx(0.0132356).epsilon(1e-5));
    CHECK(p.ci_low == doctest::Approx(3.0 - 2.7764451 * std::sqrt(0.5)).epsilon(1e-7));
    CHECK(p.ci_high == doctest::Approx(3.0 + 2.7764451 * std::sqrt(0.5)).epsilon(1e-7));
    // 99 %: t(4) quantile 4.604095.
    const TTest p99 = paired_t_test({2, 4, 6, 8, 10}, {1, 2, 3, 4, 5}, 0.99);
    CHECK(p99.ci_high - p99.mean_difference == doctest::Approx(4.6040949 * std::sqrt(0.5)).epsilon(1e-7));

    // Welch: a = 1..4 (var 5/3), b = 2, 4, 6, 8 (var 20/3): se = sqrt(5/12 + 5/3) = 1.443376,
    // t = -2.5 / se = -1.732051, df = (25/12)^2 / ((5/12)^2 / 3 + (5/3)^2 / 3) = 4.411765,
    // p = 0.151581.
    const TTest w = welch_t_test({1, 2, 3, 4}, {2, 4, 6, 8});
    REQUIRE(w.valid);
    CHECK_FALSE(w.paired);
    CHECK(w.t == doctest::Approx(-1.7320508).epsilon(1e-7));
    CHECK(w.df == doctest::Approx(4.4117647).epsilon(1e-7));
    CHECK(w.p == doctest::Approx(0.1515805).epsilon(1e-5));
    CHECK(w.ci_low < w.mean_difference);
    CHECK(w.ci_high > 0.0);  // p > 0.05: the 95 % interval holds 0
}

TEST_CASE("statistics: too few values or no variance give an invalid test, never a NaN taken as a result") {
    CHECK_FALSE(welch_t_test({1.0}, {2.0, 3.0}).valid);
    CHECK_FALSE(paired_t_test({1.0, 2.0}, {0.0, 1.0}).valid);  // differences without variance
    CHECK_THROWS(paired_t_test({1.0}, {1.0, 2.0}));
    CHECK_THROWS(welch_t_test({1.0, 2.0}, {1.0, 2.0}, 1.5));
    const Summary s = summarize({1.0, 2.0, 3.0, 4.0});
    CHECK(s.mean == 2.5);
    CHECK(s.sd == doctest::Approx(std::sqrt(5.0 / 3.0)));
}
