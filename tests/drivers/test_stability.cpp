// Closed-loop stability against the discrete passivity bound K < 2 b / T (Colgate; Gil et al.):
// the simulated arm's damping b along the contact normal and the servo period T. Below the bound
// the contact settles; above it the passivity observer reports a fault and the force goes to zero
// instead of the oscillation growing.
#include "sim_fixture.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

using namespace contactlab;
using namespace contactlab::test;

namespace {

struct PressResult {
    bool faulted = false;
    ServoFault fault = ServoFault::none;
    double max_force = 0.0;       // N, commanded
    double max_speed = 0.0;       // m/s, finger
    double late_force_pp = 0.0;   // N, peak-to-peak force over the last 0.5 s
    bool finite = true;
    double b_normal = 0.0;        // N s/m, arm damping along +y at the press point
    double b_declared = 0.0;      // N s/m
    double max_energy = 0.0;      // J, observer
};

// The hand comes down onto a floor and presses 2 mm into it (free space first: the engage gate).
PressResult press_floor(double stiffness, double rate, double hand_damping, double seconds = 1.5) {
    drivers::sim::SimCldParams sp;
    sp.hand.damping = hand_damping;
    const double R = 0.026;
    drivers::HandPath path({{0.0, {0.0, R + 0.005}, 0.0}, {0.3, {0.0, R - 0.002}, 0.0}, {seconds, {0.0, R - 0.002}, 0.0}});
    Scene scene = floor_scene(stiffness);
    ServoParams params;
    params.stiffness = stiffness;
    params.stiffness_slew = 1e9;
    SimRig rig(scene, std::move(path), rate, sp, params);
    REQUIRE(rig.opened);
    PressResult r;
    r.b_declared = rig.device.limits().damping;
    const auto ticks = static_cast<long>(std::lround(seconds * rate));
    double fmin = 1e9, fmax = -1e9;
    for (long k = 0; k < ticks; ++k) {
        rig.loop.step(1.0 / rate, true);
        const ServoSnapshot s = rig.servo.snapshot();
        r.finite = r.finite && is_finite(s.force) && is_finite(s.finger);
        r.max_force = std::max(r.max_force, glm::length(s.force));
        r.max_energy = std::max(r.max_energy, s.observer_energy);
        r.max_speed = std::max(r.max_speed, glm::length(rig.device.arm().velocity()));
        if (s.fault_count > 0 && !r.faulted) {
            r.faulted = true;
            r.fault = s.fault;
        }
        if (k > ticks - static_cast<long>(0.5 * rate)) {
            fmin = std::min(fmin, s.force.y);
            fmax = std::max(fmax, s.force.y);
        }
        if (k == static_cast<long>(0.3 * rate)) r.b_normal = rig.device.arm().cartesian_damping({0.0, 1.0});
    }
    r.late_force_pp = fmax - fmin;
    return r;
}

}  // namespace

TEST_CASE("below the passivity bound the contact settles; above it the loop reports instability") {
    const double rate = 1000.0, T = 1.0 / rate;
    const PressResult probe = press_floor(100.0, rate, 0.0, 0.4);
    const double b = probe.b_declared;
    INFO("declared damping " << b << " N s/m, along the normal " << probe.b_normal << " N s/m");
    REQUIRE(b > 0.0);
    REQUIRE(probe.b_normal >= b * (1.0 - 1e-9));

    // Below: half the declared bound, no help from the hand's damping.
    const PressResult below = press_floor(0.5 * 2.0 * b / T, rate, 0.0);
    CHECK_FALSE(below.faulted);
    CHECK(below.finite);
    CHECK(below.max_force <= 1.5 + 1e-9);
    // Settled: the force ripple left is what encoder quantisation makes (K times a few counts of
    // ~20 um), far below the pressing force.
    CHECK(below.late_force_pp < 0.1);

    // Above: four times the bound with the damping actually present along the normal.
    const double k_above = 4.0 * 2.0 * probe.b_normal / T;
    const PressResult above = press_floor(k_above, rate, 0.0);
    CHECK(above.faulted);
    CHECK(above.fault == ServoFault::instability);
    CHECK(above.finite);
    CHECK(above.max_force <= 1.5 + 1e-9);  // the clamp held while it lasted
    CHECK(above.max_speed < 1.0);          // m/s: nothing ran away
}

TEST_CASE("stability table: K vs servo rate against 2 b / T") {
    // Printed for the README; the assertions only require the ordering the theory predicts at
    // the extremes (0.5x: stable, 4x: reported).
    for (double rate : {500.0, 1000.0, 2000.0, 5000.0}) {
        const double T = 1.0 / rate;
        const PressResult probe = press_floor(100.0, rate, 0.0, 0.4);
        const double bound = 2.0 * probe.b_normal / T;
        std::printf("rate %6.0f Hz  b_n %.3f N s/m  2b/T %8.0f N/m :", rate, probe.b_normal, bound);
        for (double m : {0.5, 0.8, 1.25, 2.0, 4.0}) {
            const PressResult r = press_floor(m * bound, rate, 0.0, 1.0);
            std::printf("  %.2fx %s", m, r.faulted ? "FAULT" : (r.late_force_pp < 0.1 ? "ok" : "ripple"));
            if (m == 0.5) CHECK_FALSE(r.faulted);
            if (m == 4.0) CHECK(r.faulted);
        }
        std::printf("\n");
    }
}
