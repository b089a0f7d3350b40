// test_power_analysis.cpp — `experiment power`'s resampling (engine/experiments/analysis/power_analysis.hpp)
// against the paired t test's power computed in closed form, written here without the code under
// test: for differences ~ N(delta, 1), the test statistic follows a noncentral t with n - 1 degrees
// of freedom and noncentrality delta sqrt(n), so power = P(|T'| > t_crit) (Boost.Math's
// non_central_t). A pool of 4,000 participants stands for that population.
#include "engine/experiments/analysis/power_analysis.hpp"
#include "engine/experiments/base/results_table.hpp"

#include <boost/math/distributions/non_central_t.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>

using namespace contactlab::experiments;

namespace {

double analytic_power(double delta, int n, double alpha) {
    const double df = n - 1;
    const double crit = boost::math::quantile(boost::math::students_t(df), 1.0 - alpha / 2.0);
    const boost::math::non_central_t nct(df, delta * std::sqrt(static_cast<double>(n)));
    return boost::math::cdf(boost::math::complement(nct, crit)) + boost::math::cdf(nct, -crit);
}

// Participant i's values in two conditions, differences ~ N(delta, 1) around a common level.
void pool(double delta, int size, std::uint64_t seed, std::vector<double>& a, std::vector<double>& b) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> z(0.0, 1.0);
    a.clear(), b.clear();
    for (int i = 0; i < size; ++i) {
        const double level = 2.0 + 0.5 * z(rng);
        b.push_back(level);
        a.push_back(level + delta + z(rng));
    }
}

}  // namespace

TEST_CASE("power: the resampled power of the paired t test matches the noncentral t's") {
    std::vector<double> a, b;
    for (double delta : {0.5, 0.8}) {
        pool(delta, 4000, 7, a, b);
        PowerOptions o;
        o.sizes = {4, 6, 10, 16};
        o.resamples = 4000;
        const std::vector<PowerPoint> pts = resampled_power(a, b, o);
        REQUIRE(pts.size() == 4);
        for (const PowerPoint& p : pts) {
            const double want = analytic_power(delta, p.participants, 0.05);
            CAPTURE(delta);
            CAPTURE(p.participants);
            CAPTURE(want);
            // Monte Carlo SE sqrt(p (1 - p) / 4000) <= 0.008, and the pool's own mean and sd stray
            // from delta and 1 by about 0.016 each (power moves < 0.8 per unit of either): 0.04.
            CHECK(std::abs(p.power - want) < 0.04);
            CHECK(p.power_ci.low <= p.power);
            CHECK(p.power_ci.high >= p.power);
            CHECK(p.undefined == 0);
        }
        for (std::size_t i = 1; i < pts.size(); ++i) CHECK(pts[i].power > pts[i - 1].power);
    }
}

TEST_CASE("power: with no effect the significant share is alpha, the test's type I error") {
    std::vector<double> a, b;
    pool(0.0, 4000, 11, a, b);
    PowerOptions o;
    o.sizes = {5, 12};
    o.resamples = 4000;
    o.alpha = 0.05;
    for (const PowerPoint& p : resampled_power(a, b, o)) {
        CAPTURE(p.participants);
        CHECK(std::abs(p.power - 0.05) < 0.015);  // SE 0.0034, and the pool's mean is ~0.016 off 0
        CHECK(p.median_p > 0.4);                  // p is uniform under the null: median 0.5
    }
}

TEST_CASE("power: deterministic in the seed, and a size's figures do not depend on the other sizes") {
    std::vector<double> a, b;
    pool(0.6, 50, 3, a, b);
    PowerOptions o;
    o.sizes = {8};
    o.resamples = 500;
    const PowerPoint alone = resampled_power(a, b, o)[0];
    o.sizes = {4, 8, 12};
    const PowerPoint among = resampled_power(a, b, o)[1];
    CHECK(alone.significant == among.significant);
    o.seed = 2;
    CHECK(resampled_power(a, b, o)[1].significant != among.significant);
}

TEST_CASE("power: equal values in both conditions give undefined tests, counted and never significant") {
    const std::vector<double> a(10, 0.7), b(10, 0.7);
    PowerOptions o;
    o.sizes = {3};
    o.resamples = 100;
    const PowerPoint p = resampled_power(a, b, o)[0];
    CHECK(p.undefined == 100);
    CHECK(p.significant == 0);
    CHECK(p.power == 0.0);
}

TEST_CASE("power: from an analysis, the two conditions and each participant's measure, the rest named") {
    using nlohmann::json;
    json analysis = {{"conditions",
                      {{"F", {{"participants", {{"1", {{"it_est_bits", 1.0}}}, {"2", {{"it_est_bits", 1.2}}}, {"3", {{"it_est_bits", 0.9}}}}}}},
                       {"F+CLD",
                        {{"participants",
                          {{"1", {{"it_est_bits", 1.4}}}, {"2", {{"it_est_bits", 1.5}}}, {"3", {{"it_est_bits", nullptr}}}}}}}}}};
    PowerOptions o;
    o.sizes = {4};
    o.resamples = 200;
    const json r = power_analysis(analysis, o);
    CHECK(r["pool"] == 2);
    CHECK(r["conditions"] == json::array({"F", "F+CLD"}));
    REQUIRE(r["left_out"].size() == 1);
    CHECK(r["left_out"][0]["participant"] == "3");
    CHECK(r["pool_effect"]["mean_difference"].get<double>() == doctest::Approx(-0.35));
    REQUIRE(r["points"].size() == 1);
    CHECK(r["points"][0]["participants"] == 4);
    o.measure = "time_s";
    CHECK_THROWS_WITH_AS(power_analysis(analysis, o), doctest::Contains("no per-participant time_s"), ExperimentError);
    o.measure = "it_est_bits";
    analysis["conditions"]["third"] = analysis["conditions"]["F"];
    CHECK_THROWS_WITH_AS(power_analysis(analysis, o), doctest::Contains("--conditions A,B"), ExperimentError);
    o.condition_a = "F";
    o.condition_b = "third";
    CHECK(power_analysis(analysis, o)["pool_effect"]["mean_difference"].get<double>() == 0.0);  // a condition against its copy
}
