// test_intervals.cpp — the report's intervals (engine/experiments/analysis/intervals.hpp) against published
// values: Wilson's score interval from Newcombe (1998), Stat. Med. 17:857, Table I (method 3), and
// a t interval worked by hand.
#include "engine/experiments/analysis/intervals.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace contactlab::experiments;

TEST_CASE("wilson interval: Newcombe's four examples at 95 %, to the 4 decimals he gives") {
    struct Case {
        long r, n;
        double low, high;
    };
    for (const Case& c : {Case{81, 263, 0.2553, 0.3662}, Case{15, 148, 0.0624, 0.1605}, Case{0, 20, 0.0, 0.1611},
                          Case{1, 29, 0.0061, 0.1718}}) {
        const Interval i = wilson_interval(c.r, c.n, 0.95);
        CAPTURE(c.r);
        CAPTURE(c.n);
        CHECK(std::abs(i.low - c.low) <= 5e-5);
        CHECK(std::abs(i.high - c.high) <= 5e-5);
    }
}

TEST_CASE("wilson interval: inside [0, 1] at the ends, wider at 99 % than at 95 %, NaN with no trials") {
    const Interval all = wilson_interval(20, 20, 0.99), none = wilson_interval(0, 20, 0.99);
    CHECK(all.high == 1.0);
    CHECK(all.low > 0.0);
    CHECK(none.low == 0.0);
    CHECK(none.high < 1.0);
    const Interval i95 = wilson_interval(13, 20, 0.95), i99 = wilson_interval(13, 20, 0.99);
    CHECK(i99.low < i95.low);
    CHECK(i99.high > i95.high);
    CHECK(std::isnan(wilson_interval(0, 0, 0.95).low));
}

TEST_CASE("mean interval: 1..5 at 95 % is 3 +- t(4) sd / sqrt(5)") {
    // sd = sqrt(2.5), se = sqrt(0.5); t_{0.975, 4} = 2.7764451 (tables).
    const Interval i = mean_interval({1, 2, 3, 4, 5}, 0.95);
    CHECK(i.low == doctest::Approx(3.0 - 2.7764451 * std::sqrt(0.5)).epsilon(1e-7));
    CHECK(i.high == doctest::Approx(3.0 + 2.7764451 * std::sqrt(0.5)).epsilon(1e-7));
    CHECK(standard_error({1, 2, 3, 4, 5}) == doctest::Approx(std::sqrt(0.5)));
    CHECK(std::isnan(mean_interval({1.0}, 0.95).low));
}
