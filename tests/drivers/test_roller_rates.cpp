// The roller loop at every servo rate 100 Hz-20 kHz: below 1 kHz the controller re-places the
// design's poles at p T = 0.4 (haptics/roller_controller.hpp, RollerGains::pole), so the loop is
// the 1 kHz loop slowed by T / 1 ms; at and above 1 kHz the continuous-time gains are used as
// given. And whatever the rate or the integral gain, the loop stays bounded: the anti-windup
// (conditional integration, integral clamped to the drive's rail) holds even at 1000 x Ki.
#include "drivers/sim/bench_probes.hpp"
#include "drivers/sim/roller_sine.hpp"

#include <doctest/doctest.h>

#include <cstdio>

using namespace contactlab;
using drivers::sim::RollerStepRun;
using drivers::sim::roller_step_run;

namespace {

constexpr double kRates[] = {100.0, 250.0, 500.0, 1000.0, 4000.0, 10000.0, 20000.0};  // Hz
// m: one count of the roller's motor encoder (1024 lines x 4 on an M4 x 0.7 lead): 0.17 um.
const double kCount = drivers::sim::RollerParams{}.lead / drivers::sim::RollerParams{}.encoder_counts;

// Whatever happens, the loop must keep these.
void check_bounded(const RollerStepRun& r, const RollerGains& g) {
    CHECK(r.finite);
    CHECK(r.max_drive <= g.max_drive + 1e-12);  // V
    // The travel is +-10 mm; the hard stop is where the nut would stop a runaway.
    CHECK(r.max_nut <= 0.5 * drivers::sim::RollerParams{}.travel + 1e-9);
}

}  // namespace

TEST_CASE("roller: the re-placed poles follow the sampling below 1 kHz, the design is kept from 1 kHz up") {
    const RollerGains g;
    for (double rate : kRates) {
        const RollerGains used = sampled_roller_gains(g, 1.0 / rate);
        CAPTURE(rate);
        if (g.pole / rate <= g.max_pole_period) {
            CHECK(used.kp == g.kp);
            CHECK(used.ki == g.ki);
            CHECK(used.kd == g.kd);
        } else {
            const double s = g.max_pole_period * rate / g.pole;  // p_new / p
            CHECK(used.kp == doctest::Approx(g.kp * s * s));
            CHECK(used.ki == doctest::Approx(g.ki * s * s * s));
            // Kd + 1 / g = 3 tau p / g scales with p.
            CHECK(used.kd + g.back_emf == doctest::Approx((g.kd + g.back_emf) * s));
        }
    }
}

TEST_CASE("roller: steps settle and the loop stays bounded at every rate from 100 Hz to 20 kHz") {
    // Holds of 0.4 s after steps of up to 16 mm (the drive saturates for tens of ms). Settled: the
    // error over each hold's last 20 % within 25 um at 100 Hz, where the triple pole is at 40
    // rad/s and 0.32 s is 13 / p (the stiction band of the nut makes a small residual), and within
    // 10 counts (1.7 um) from 250 Hz up, where it is 40x as many time constants.
    for (double rate : kRates) {
        const RollerGains g;
        const RollerStepRun r = roller_step_run(drivers::sim::RollerParams{}, g, rate);
        CAPTURE(rate);
        check_bounded(r, g);
        // Or, where more, the stiction band: the nut stays stuck while the P drive, Kp' e (Kp'
        // re-placed at this rate), is under the break-away voltage, and the integral then creeps
        // it in (with the velocity feed-forward the holds start from another point in that band:
        // 3.1 um seen at 250 Hz, under this bound's 15 um there; 1 um at 1 kHz and up).
        const drivers::sim::RollerParams plant;
        const double volts_per_newton = plant.resistance / (plant.torque_constant * 2.0 * 3.141592653589793 / plant.lead);
        const double stuck_band = plant.stiction * volts_per_newton / sampled_roller_gains(g, 1.0 / rate).kp;  // m
        CHECK(r.max_settle_error <= (rate < 200.0 ? 25e-6 : std::max(10.0 * kCount, stuck_band)));
        // A triple real pole never overshoots; what the saturated drive and stiction add stays
        // under 1 mm of a 16 mm step.
        CHECK(r.max_overshoot < 1e-3);
    }
}

TEST_CASE("roller: the same gains without re-placing limit-cycle below 500 Hz, re-placed they settle") {
    // The contrast that makes the re-placement necessary (and this test able to fail): at 100 and
    // 250 Hz the design's p T is 4 and 1.6, beyond the sampling's reach.
    for (double rate : {100.0, 250.0}) {
        RollerGains frozen;
        frozen.pole = 0.0;  // gains as given at every rate
        const RollerStepRun f = roller_step_run(drivers::sim::RollerParams{}, frozen, rate);
        const RollerStepRun r = roller_step_run(drivers::sim::RollerParams{}, RollerGains{}, rate);
        CAPTURE(rate);
        check_bounded(f, frozen);
        CHECK(f.max_settle_error > 0.1e-3);  // m: a limit cycle of tenths of a mm or more
        CHECK(r.max_settle_error < 0.1 * f.max_settle_error);
    }
}

TEST_CASE("roller: anti-windup holds at 1000 x Ki at every rate") {
    // Ki x 1000 puts the linear loop far past stability; what keeps it bounded is that the integral
    // never leaves the rail (+-12 V) and stops integrating while saturated. Bounded: finite, on the
    // rail, inside the travel, and a step never overshoots by more than 2.5 mm (seen: <= 2.0 mm).
    for (double rate : kRates) {
        RollerGains g;
        g.ki *= 1000.0;
        const RollerStepRun r = roller_step_run(drivers::sim::RollerParams{}, g, rate);
        CAPTURE(rate);
        check_bounded(r, g);
        CHECK(r.max_overshoot < 2.5e-3);
        // m: never lost the 5 mm sine by much more than its amplitude (seen: 3.6 mm with seed 000's
        // pure eq. 2, 5.1 mm at 100 Hz with the default velocity feed-forward, which pushes the
        // rail-to-rail limit cycle of this far-unstable loop further; 0.7 mm from 250 Hz up).
        CHECK(r.max_sine_error < 6e-3);
    }
}

TEST_CASE("roller: block task error below 1 kHz grows no faster than the period") {
    // The loop below 1 kHz is the 1 kHz loop slowed by T / 1 ms, so a ramp's lag grows like T:
    // error(rate) <= error(1 kHz) x (1 kHz / rate), 10 % for the encoder's and the angle
    // encoder's steps (which do not scale). The block is 250 N/m so the contact stays inside the
    // arm's 2 b / T at 100 Hz (343 N/m). Printed: the figures docs/simulation.md gives.
    const double speed = 0.05;  // m/s
    const drivers::sim::BlockTracking k1 = drivers::sim::block_task_tracking(speed, 1000.0, RollerGains{}, 250.0);
    REQUIRE(k1.opened);
    REQUIRE(k1.samples > 0);
    for (double rate : {100.0, 250.0, 500.0}) {
        const drivers::sim::BlockTracking tr = drivers::sim::block_task_tracking(speed, rate, RollerGains{}, 250.0);
        RollerGains frozen;
        frozen.pole = 0.0;
        const drivers::sim::BlockTracking fr = drivers::sim::block_task_tracking(speed, rate, frozen, 250.0);
        REQUIRE(tr.opened);
        REQUIRE(tr.samples > 0);
        std::printf("roller block task 5 cm/s at %.0f Hz: max %.3f mm, rms %.3f mm (1 kHz: %.3f mm; gains as "
                    "given: %.3f mm)\n",
                    rate, tr.max_measured * 1e3, tr.rms_measured * 1e3, k1.max_measured * 1e3, fr.max_measured * 1e3);
        CAPTURE(rate);
        CHECK(tr.max_measured <= 1.1 * k1.max_measured * (1000.0 / rate));
        // And never worse than the same gains used as given (at 500 Hz they still hold, p T 0.8).
        CHECK(tr.max_measured <= fr.max_measured * 1.02);
    }
}
