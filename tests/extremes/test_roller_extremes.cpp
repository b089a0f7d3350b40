// test_roller_extremes.cpp — the roller PID (seed 000 eq. 2) at the extremes: gains 1e-6x and 1e6x
// nominal, a huge Ki that would wind up without anti-windup, rates 100 Hz to 100 kHz, jittered and
// broken periods, absurd targets and non-finite gains. Against a plant with the simulated CLD
// roller's small-signal model (roller_controller.hpp): l' = g v, v' = (u - v) / tau.
#include <doctest/doctest.h>

#include "haptics/roller_controller.hpp"

#include <cmath>
#include <limits>
#include <random>

using namespace contactlab;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The roller's small-signal plant: drive u (V) -> nut speed through a 16 ms lag, 0.0223 m/(V s),
// integrated exactly over each period; hard stops at the travel ends (m).
struct RollerPlant {
    double g = 0.0223;   // m/(V s)
    double tau = 0.016;  // s
    double l = 0.0;      // m
    double v = 0.0;      // V, the lagged drive
    RollerTravel travel;
    void advance(double u, double dt) {
        const double a = std::exp(-dt / tau);
        // Exact zero-order-hold integration of v' = (u - v)/tau, l' = g v.
        l += g * (u * dt + (v - u) * tau * (1.0 - a));
        v = u + (v - u) * a;
        if (l > travel.max) { l = travel.max; v = std::min(v, 0.0); }
        if (l < travel.min) { l = travel.min; v = std::max(v, 0.0); }
    }
};

RollerGains scaled(double factor) {
    RollerGains g;
    g.kp *= factor;
    g.ki *= factor;
    g.kd *= factor;
    return g;
}

}  // namespace

TEST_CASE("gains 1e-6x to 1e6x at 100 Hz to 100 kHz, jittered periods: the drive stays finite and within its limit") {
    std::mt19937_64 rng(7);
    for (double factor : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
        for (double rate : {100.0, 1e3, 1e4, 1e5}) {
            for (bool jitter : {false, true}) {
                CAPTURE(factor);
                CAPTURE(rate);
                CAPTURE(jitter);
                const RollerGains gains = scaled(factor);
                RollerController c(gains, RollerTravel{});
                RollerPlant plant;
                std::uniform_real_distribution<double> spread(0.2, 1.8);  // x the nominal period
                const double T = 1.0 / rate;  // s
                double t = 0.0;
                while (t < 0.5) {
                    const double dt = jitter ? T * spread(rng) : T;
                    const double target = 0.008 * std::sin(2.0 * 3.141592653589793 * 2.0 * t);  // m, 2 Hz
                    const double u = c.step(target, plant.l, dt);
                    REQUIRE(std::isfinite(u));
                    REQUIRE(std::abs(u) <= gains.max_drive);
                    plant.advance(u, dt);
                    REQUIRE(std::isfinite(plant.l));
                    t += dt;
                }
            }
        }
    }
}

TEST_CASE("Ki at 1e6x nominal: no windup, the drive leaves saturation the tick the error reverses") {
    RollerGains g;
    g.ki *= 1e6;  // V/(m s)
    RollerController c(g, RollerTravel{});
    const double dt = 1e-3;  // s
    // One second pushing against a roller stuck at l = 0 with the target at the travel end.
    for (int k = 0; k < 1000; ++k) {
        const double u = c.step(0.010, 0.0, dt);
        REQUIRE(u == doctest::Approx(g.max_drive));
    }
    // The target reverses: a wound-up integral (1e6 x 4.6e7 V/(m s) x 1 cm x 1 s) would hold the
    // drive at +max for ages; conditional integration keeps it within the output range, so the
    // proportional term (Kp x 1 cm = 3450 V) takes the drive to -max at once.
    const double u = c.step(-0.010, 0.0, dt);
    CHECK(u == doctest::Approx(-g.max_drive));
}

TEST_CASE("absurd targets and broken periods give a finite drive") {
    RollerController c;
    for (double target : {1e3, -1e3, 1e300, -1e300}) {
        const double u = c.step(target, 0.0, 1e-3);
        CHECK(std::isfinite(u));
        CHECK(std::abs(u) <= c.gains().max_drive);
        // The target is held within the travel.
        CHECK(c.target() >= c.travel().min);
        CHECK(c.target() <= c.travel().max);
    }
    for (double dt : {0.0, -1e-3, kNaN, kInf, 1e-12, 10.0}) {
        CAPTURE(dt);
        const double u = c.step(0.005, 0.0, dt);
        CHECK(std::isfinite(u));
        CHECK(std::abs(u) <= c.gains().max_drive);
    }
}

TEST_CASE("non-finite or negative gains hold the roller still (zero drive) instead of driving it wild") {
    for (double bad : {kNaN, kInf, -kInf, -1.0}) {
        for (int which = 0; which < 10; ++which) {
            CAPTURE(bad);
            CAPTURE(which);
            RollerGains g;
            REQUIRE(roller_gains_usable(g));
            double* fields[] = {&g.kp,   &g.ki,   &g.kd,   &g.d_cutoff_hz, &g.max_drive, &g.pole, &g.max_pole_period,
                                &g.back_emf, &g.kff, &g.ff_cutoff_hz};
            *fields[which] = bad;
            CHECK_FALSE(roller_gains_usable(g));
            RollerController c(g, RollerTravel{});
            for (int k = 0; k < 50; ++k) {
                // Error zero on some ticks (inf x 0 = NaN) and not on others.
                const double u = c.step(k % 2 == 0 ? 0.0 : 0.001, 0.0, 1e-3);
                // The leadscrew is not backdrivable: zero drive holds the roller where it is.
                CHECK(u == 0.0);
            }
        }
    }
}
