// Closed-loop stability against the discrete passivity bound K < 2 b / T (Colgate; Gil et al.):
// the simulated arm's damping b along the contact normal and the servo period T. Below the bound
// the contact settles; above it the passivity observer reports a fault and the force goes to zero
// instead of the oscillation growing.
#include "sim_fixture.hpp"

#include "drivers/sim/bench_probes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

using namespace contactlab;
using namespace contactlab::test;
// The press, the bisection and the table are library code (drivers/sim/bench_probes.hpp), shared
// with `contactlab bench`: the numbers checked here are the ones the bench reports.
using drivers::sim::press_floor;
using drivers::sim::PressResult;

// (No ';' in test names: doctest_discover_tests splits names there, and the halves match nothing.)
TEST_CASE("below the passivity bound the contact settles, above it the loop reports instability") {
    const double rate = 1000.0, T = 1.0 / rate;
    const PressResult probe = press_floor(100.0, rate, 0.0, 0.4);
    REQUIRE(probe.opened);
    const double b = probe.b_declared;
    INFO("declared damping " << b << " N s/m, along the normal " << probe.b_normal << " N s/m");
    REQUIRE(b > 0.0);
    REQUIRE(probe.b_normal >= b * (1.0 - 1e-9));

    // Below: half the declared bound, no help from the hand's damping.
    const PressResult below = press_floor(0.5 * 2.0 * b / T, rate, 0.0);
    REQUIRE(below.opened);
    CHECK_FALSE(below.faulted);
    CHECK(below.finite);
    CHECK(below.max_force <= 1.5 + 1e-9);
    // Settled: the force ripple left is what encoder quantisation makes (K times a few counts of
    // ~20 um), far below the pressing force.
    CHECK(below.late_force_pp < 0.1);

    // Above: four times the bound with the damping actually present along the normal.
    const double k_above = 4.0 * 2.0 * probe.b_normal / T;
    const PressResult above = press_floor(k_above, rate, 0.0);
    REQUIRE(above.opened);
    CHECK(above.faulted);
    CHECK(above.fault == ServoFault::instability);
    CHECK(above.finite);
    CHECK(above.max_force <= 1.5 + 1e-9);  // the clamp held while it lasted
    CHECK(above.max_speed < 1.0);          // m/s: nothing ran away
}

TEST_CASE("stability table: largest stable K vs servo rate against 2 b / T") {
    // The sampled spring on a mass m with damping b, force held over T: z^2 + (aT + k - 2) z +
    // (1 - aT + k) with a = b / m, k = K T^2 / (2 m) (to first order in aT), whose roots leave the
    // unit circle when k > aT, i.e. K > 2 b / T (Colgate and Schenkel's bound). With the sampling
    // alone ("ideal": 24-bit encoders, 75 nm at the endpoint, and no joint friction) the largest
    // settled K must sit at the bound. Band [0.75, 1.25] x 2b/T: "settled" asks the ripple to fall
    // 10% in 0.25 s, and the decay rate (1 - K / K_c) a / 2 (a = b / m ~ 11 /s) is that fast only
    // below ~0.93 K_c; the bisection's 2%, the second-order terms in aT <= 0.07 and the arm's
    // coupling to the tangential direction take a few percent more either way.
    // On the rig, the joints' Coulomb friction (regularised below 1e-3 rad/s, so it damps small
    // motions) adds margin, and its 16-bit encoders (~19 um a count at the endpoint) give a
    // quantisation limit cycle of K x counts that passes 0.1 N near 5000 N/m at any rate: printed.
    std::printf("stability table (hand without damping, 2 mm press, 1 s; largest K by bisection to 2%%; "
                "unreported: observer quiet; settled: also the force ripple small or dying out):\n");
    std::printf("| rate | b (N s/m) | 2b/T (N/m) | rig: unreported | rig: settled | ideal: unreported | ideal: settled |\n");
    const std::vector<StabilityRow> rows = stability_table(false);
    REQUIRE(rows.size() == 4);
    for (const StabilityRow& row : rows) {
        const double bound = row.passivity_bound;  // N/m
        std::printf("| %.0f Hz | %.3f | %.0f |", row.rate_hz, row.b_normal, bound);
        CHECK(row.search_lo == doctest::Approx(0.2 * bound));
        CHECK(row.search_hi == doctest::Approx(4.0 * bound));
        for (bool ideal : {false, true}) {
            for (bool settled : {false, true}) {
                const double k = ideal ? (settled ? row.k_ideal_settles : row.k_ideal_no_fault)
                                       : (settled ? row.k_settles : row.k_no_fault);
                std::printf(" %s%.0f (%.2f) |", k >= row.search_hi ? ">= " : "", k, k / bound);
                // 0 would mean the loop failed even at 0.2 x the bound: the bracket's low end must hold.
                CHECK(k >= row.search_lo);
                if (ideal && settled) {
                    CHECK(k >= 0.75 * bound);
                    CHECK(k <= 1.25 * bound);
                }
                if (!settled) {
                    // The observer: never a false alarm below the bound, and a report before 4x
                    // wherever the spring's linear range (max_force / K) spans at least two encoder
                    // counts at 4x (one count at the endpoint is at most (l1 + l2) 2 pi / counts:
                    // 38 um on the rig, 75 nm ideal); with fewer, the sensed spring is a relay and
                    // the loop a quantisation limit cycle the energy sums cannot resolve.
                    const drivers::sim::PlanarArmParams arm;
                    const double count = (arm.l1 + arm.l2) * 2.0 * 3.141592653589793 / (ideal ? (1 << 24) : arm.encoder_counts);
                    CHECK(k >= bound);
                    if (1.5 / (4.0 * bound) >= 2.0 * count) CHECK(k < 4.0 * bound);
                }
            }
        }
        std::printf("\n");
    }
}

TEST_CASE("quick stability table: the full table's rows at 250 Hz and 1 kHz, the ideal arm settling at 2 b / T") {
    // The bench's --quick run: fewer rates, the same bisection, so the same numbers as the full
    // table at those rates (the full table is checked above; here the physics band on what the
    // quick run reports, without running the full table again).
    const std::vector<StabilityRow> quick = stability_table(true);
    REQUIRE(quick.size() == 2);
    CHECK(quick[0].rate_hz == 250.0);
    CHECK(quick[1].rate_hz == 1000.0);
    for (const StabilityRow& row : quick) {
        INFO(row.rate_hz << " Hz: 2b/T " << row.passivity_bound << " N/m, ideal settled " << row.k_ideal_settles
                         << " N/m, rig settled " << row.k_settles << " N/m, rig unreported " << row.k_no_fault << " N/m");
        CHECK(row.passivity_bound == doctest::Approx(2.0 * row.b_normal * row.rate_hz));
        // The band of the full table's test: sampling alone puts the settling limit at the bound.
        CHECK(row.k_ideal_settles >= 0.75 * row.passivity_bound);
        CHECK(row.k_ideal_settles <= 1.25 * row.passivity_bound);
        // And no false alarm below the bound, rig or ideal.
        CHECK(row.k_no_fault >= row.passivity_bound);
        CHECK(row.k_ideal_no_fault >= row.passivity_bound);
        // Settling is the stricter test: never above what merely goes unreported.
        CHECK(row.k_settles <= row.k_no_fault);
        CHECK(row.k_ideal_settles <= row.k_ideal_no_fault);
    }
}
