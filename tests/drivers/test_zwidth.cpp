// The Z-width of the simulated rig (drivers/sim/bench_probes.hpp, ZWidthRow): the largest stable
// stiffness K against the scene's normal damping B, pressed and sliding, at 1 and 10 kHz, the rows
// `contactlab bench --quick` reports. Checked against the physics of a sampled spring and
// backward-difference damper on a damped mass (T the period, b the arm's damping, B_a the damping
// the servo applies):
//   - passivity (Colgate and Schenkel): b > K T / 2 + |B_a|, K_max = 2 (b - |B_a|) / T;
//   - stability to first order in T (Gil et al. 2004): the held spring adds K T / 2 of negative
//     damping, the damper, delayed by a period, B_a of positive: K_max = 2 (b + B_a) / T;
//   - the encoders' counts (Delta ~ 18 um): a settled contact still dithers by a count, which
//     the spring turns into K Delta of force ripple and the damper, as velocity steps of
//     +-Delta / dt (dt the damper's divisor), into 2 B Delta / dt; at the 0.1 N "settled" limit
//     K = 0.1 N / Delta - 2 B / dt, falling by 2 / dt per N s/m.
#include "drivers/sim/bench_probes.hpp"
#include "drivers/sim/stability_probes.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace contactlab;
using namespace contactlab::drivers::sim;  // the single measurements: damper_response, largest_stable_k, ...

namespace {

// The bench's quick table, computed once for every test case here (about 4 s of CPU).
const std::vector<ZWidthRow>& quick_rows() {
    static const std::vector<ZWidthRow> rows = [] {
        std::vector<ZWidthRow> r = zwidth_table(true);
        std::printf("Z-width, quick (K in N/m):\n| rate | B | B_a | press stable | slide stable | press no fault | "
                    "slide no fault | 2(b_n-B_a)/T | 2(b_d-B_a)/T | 2(b_n+B_a)/T |\n");
        for (const ZWidthRow& z : r)
            std::printf("| %.0f | %.2f | %.3f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f |\n", z.rate_hz, z.damping,
                        z.damping_applied, z.k_press, z.k_slide, z.k_press_no_fault, z.k_slide_no_fault, z.bound_normal,
                        z.bound_declared, 2.0 * (z.b_normal + std::abs(z.damping_applied)) * z.rate_hz);
        return r;
    }();
    return rows;
}

std::vector<ZWidthRow> rows_at(double rate) {
    std::vector<ZWidthRow> out;
    for (const ZWidthRow& z : quick_rows())
        if (z.rate_hz == rate) out.push_back(z);
    return out;
}

// The first-order stability limit, N/m.
double stability_limit(const ZWidthRow& z) { return 2.0 * (z.b_normal + std::abs(z.damping_applied)) * z.rate_hz; }

}  // namespace

TEST_CASE("the servo's damper is a backward difference of the sampled position, B per m/s at every rate") {
    // What Colgate's model assumes: F = K d + B (x_k - x_{k-1}) / T, the velocity from the last two
    // encoder samples and nothing older, T the servo's own period. (The servo once left the proxy
    // at its default 1 ms: B x 1 ms / T was applied, a tenth of B at 10 kHz.)
    for (const double rate : {250.0, 1000.0, 4000.0, 10000.0}) {
        for (const double b : {0.5, 1.0, 2.0}) {
            CAPTURE(rate);
            CAPTURE(b);
            const DamperResponse r = damper_response(b, rate);
            CHECK(r.applied == doctest::Approx(b).epsilon(1e-6));
            CHECK(std::abs(r.after_stop) < 1e-9);  // N: one tick after the motion stops, no damper force
        }
        CHECK(std::abs(damper_response(0.0, rate).applied) < 1e-9);
    }
}

TEST_CASE("Z-width at B = 0 is the stability table's press, settled and unreported, at 1 and 10 kHz") {
    for (const double rate : {1000.0, 10000.0}) {
        CAPTURE(rate);
        const std::vector<ZWidthRow> rows = rows_at(rate);
        REQUIRE_FALSE(rows.empty());
        const ZWidthRow& z = rows.front();
        REQUIRE(z.damping == 0.0);
        CHECK(z.search_lo == doctest::Approx(0.05 * 2.0 * z.b_normal * rate));
        CHECK(z.search_hi == doctest::Approx(4.0 * 2.0 * z.b_normal * rate));
        // The stability table's bisections at this rate (StabilityRow::k_settles, k_no_fault): the
        // same press and bracket, so the same figure to within the bisection's resolution.
        const double settles = largest_stable_k(rate, z.search_lo, z.search_hi, true, false, z.resolution);
        const double no_fault = largest_stable_k(rate, z.search_lo, z.search_hi, false, false, z.resolution);
        INFO("table: settles " << settles << ", no fault " << no_fault << "; Z-width: " << z.k_press << ", "
                               << z.k_press_no_fault);
        CHECK(z.k_press <= settles * z.resolution);
        CHECK(z.k_press >= settles / z.resolution);
        CHECK(z.k_press_no_fault <= no_fault * z.resolution);
        CHECK(z.k_press_no_fault >= no_fault / z.resolution);
    }
}

TEST_CASE("Z-width: the JSON-facing rows are complete and self-consistent") {
    const std::vector<ZWidthRow>& rows = quick_rows();
    REQUIRE(rows.size() == 8);  // 1 kHz: B = 0, 0.5, 1, 2, 5; 10 kHz: B = 0, 1, 2
    for (const ZWidthRow& z : rows) {
        CAPTURE(z.rate_hz);
        CAPTURE(z.damping);
        CHECK(z.resolution == doctest::Approx(1.02));
        CHECK(z.damping_applied == doctest::Approx(effective_damping(z.damping, z.rate_hz)));
        CHECK(z.bound_normal == doctest::Approx(2.0 * (z.b_normal - std::abs(z.damping_applied)) * z.rate_hz));
        CHECK(z.bound_declared == doctest::Approx(2.0 * (z.b_declared - std::abs(z.damping_applied)) * z.rate_hz));
        CHECK(z.b_declared < z.b_normal);  // the declared damping is the lowest over the workspace
        // Every K is a bisection result: in the bracket, or 0 (not even its low end held).
        for (const double k : {z.k_press, z.k_slide, z.k_press_no_fault, z.k_slide_no_fault}) {
            CHECK(std::isfinite(k));
            CHECK((k == 0.0 || (k >= z.search_lo && k <= z.search_hi)));
        }
        // Settling is the stricter test (to within the two bisections' resolution).
        CHECK(z.k_press <= z.k_press_no_fault * z.resolution);
        CHECK(z.k_slide <= z.k_slide_no_fault * z.resolution);
        // No fault wherever Colgate's bound with the damping the servo knows (the declared b: the
        // press's, and the stroke's over its wider box) calls the loop passive: the detectors
        // report generation, not a passive wall.
        const double slide_declared = 2.0 * (declared_damping(ContactScenario::slide) - std::abs(z.damping_applied)) * z.rate_hz;
        CHECK(z.k_press_no_fault >= std::max(0.0, z.bound_declared) / z.resolution);
        CHECK(z.k_slide_no_fault >= std::max(0.0, slide_declared) / z.resolution);
    }
}

TEST_CASE("Z-width at 1 kHz: virtual damping raises the unreported K along 2 (b + B) / T") {
    // Stability, not passivity: the damper's B adds to the arm's b against the held spring's
    // K T / 2. Band [0.8, 1.35]: at B = 0 the joints' Coulomb friction adds margin (the stability
    // table's 1 kHz rig reports from 1.29 x 2b/T); the damper's delay also subtracts a mass B T
    // (5 g at 5 N s/m against the arm's ~0.1 kg) and the spring's second-order terms (K T^2 / m)
    // take a few percent at 2.5 x the B = 0 limit; and the bisection's 2 %.
    const std::vector<ZWidthRow> rows = rows_at(1000.0);
    REQUIRE(rows.size() == 5);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const ZWidthRow& z = rows[i];
        CAPTURE(z.damping);
        CHECK(z.damping_applied == doctest::Approx(z.damping).epsilon(1e-6));
        const double limit = stability_limit(z);
        CHECK(z.k_press_no_fault >= 0.8 * limit);
        CHECK(z.k_press_no_fault <= 1.35 * limit);
        // Sliding adds the stroke's motion across the normal, not another loop: the same limit to
        // within the coupling of the arm's tangential motion (and a declared b 2 % lower).
        CHECK(z.k_slide_no_fault >= 0.8 * z.k_press_no_fault);
        CHECK(z.k_slide_no_fault <= 1.25 * z.k_press_no_fault);
        if (i > 0) CHECK(z.k_press_no_fault >= rows[i - 1].k_press_no_fault / z.resolution);  // rises with B
        // Passivity is sufficient: at 1 kHz a count of the encoders times 2 b_n / T is 0.06 N, under
        // the 0.1 N settling limit, so every K the bound calls passive also settles.
        if (z.bound_normal > 0.0) CHECK(z.k_press >= z.bound_normal / z.resolution);
    }
    // Past b the passivity bound has nothing left (no K is passive), yet the loop holds more than
    // twice the B = 0 bound unreported.
    CHECK(rows.back().bound_normal < 0.0);
    CHECK(rows.back().k_press_no_fault > 2.0 * 2.0 * rows.back().b_normal * 1000.0);
}

TEST_CASE("Z-width: the settled K falls as B grows, by 2 / dt per N s/m (the damper's velocity steps)") {
    // Where settling, not a fault, sets the limit (settled K under the unreported one), the
    // ripple is the encoders' one-count dither, Delta (K + 2 B / dt) at the 0.1 N limit: K falls
    // linearly with B, slope 2 / dt = 2 B_a / (B T), whatever Delta is. Band [0.75, 1.25]: the
    // dither is not exactly one count of each, and each figure carries the bisection's 2 %
    // (over 0.5 N s/m steps of 1000 N/m, 4 % of the slope). Falling is the passivity bound's
    // direction too (2 / T per N s/m), but here it is the encoders', not the sampling's.
    // At 10 kHz the line leaves the bracket at once: one count (~18 um) in one 0.1 ms tick is
    // 0.18 m/s, so B = 1 N s/m alone steps the force by 2 B Delta / dt = 0.36 N, over the 0.1 N
    // budget; nothing settles there from B = 1 on, which the last check below holds.
    for (const double rate : {1000.0, 10000.0}) {
        CAPTURE(rate);
        const std::vector<ZWidthRow> rows = rows_at(rate);
        REQUIRE(rows.size() >= 3);
        int slopes = 0;
        for (std::size_t i = 1; i < rows.size(); ++i) {
            const ZWidthRow &a = rows[i - 1], &b = rows[i];
            CAPTURE(b.damping);
            // Monotone from the first B where settling is what limits (B >= 0.5 N s/m at 1 kHz,
            // where the fault limits at B = 0; everywhere at 10 kHz).
            const bool ripple_limited = a.k_press < a.k_press_no_fault / a.resolution;
            if (!ripple_limited && a.damping == 0.0) continue;
            CHECK(b.k_press <= a.k_press * b.resolution);
            // The line, where it stays in the bracket (past that, K Delta is no longer what the
            // ripple is made of: 448 N/m still settles at 1 kHz, 5 N s/m, a near-rigid damper).
            const double expected = 2.0 * b.damping_applied / (b.damping * (1.0 / rate));  // N/m per N s/m
            const bool on_line = a.k_press - expected * (b.damping - a.damping) >= b.search_lo;
            if (ripple_limited && on_line && b.k_press > 0.0 && b.k_press < b.k_press_no_fault / b.resolution) {
                const double slope = (a.k_press - b.k_press) / (b.damping - a.damping);  // N/m per N s/m
                INFO("slope " << slope << " N/m per N s/m, expected " << expected);
                CHECK(slope >= 0.75 * expected);
                CHECK(slope <= 1.25 * expected);
                ++slopes;
            }
        }
        if (rate == 1000.0) CHECK(slopes >= 1);
        // Enough damping leaves no K that settles in the bracket: the damper's velocity steps alone
        // (2 B Delta / dt, 0.07 N at 2 N s/m, 0.18 N at 5) fill the 0.1 N budget.
        CHECK(rows.back().k_press < rows.front().k_press / 2.0);
        // Sliding, from B = 1 N s/m on the damper's steps set the limit in the same way.
        for (std::size_t i = 1; i < rows.size(); ++i)
            if (rows[i - 1].damping >= 1.0) CHECK(rows[i].k_slide <= rows[i - 1].k_slide * rows[i].resolution);
    }
}

TEST_CASE("Z-width at 10 kHz: the unreported K is at most the declared bound, where the limit-cycle detector arms") {
    // K T / 2 > b_declared arms the detector whatever B is, and from 4 kHz up it then reports the
    // quantisation limit cycle (the stability table's 4-20 kHz rows): unreported K = 2 b_d / T to
    // within the bisection at B = 0. With a damper the encoders' one-count steps (0.18 m/s in a
    // 0.1 ms tick) put 2 B Delta / dt into the force, 0.36 N per N s/m: past the detector's 0.45 N
    // swing the dither itself is reported, so the unreported K can only fall below the armed bound.
    // The stroke's rig declares its own (lower) b, over the stroke's box.
    const double slide_b = declared_damping(ContactScenario::slide);  // N s/m
    for (const ZWidthRow& z : rows_at(10000.0)) {
        CAPTURE(z.damping);
        const double armed = 2.0 * z.b_declared * z.rate_hz, slide_armed = 2.0 * slide_b * z.rate_hz;  // N/m
        if (z.damping == 0.0) {
            CHECK(z.k_press_no_fault >= armed / z.resolution);
            CHECK(z.k_slide_no_fault >= slide_armed / z.resolution);
        }
        CHECK(z.k_press_no_fault <= 1.05 * armed);
        CHECK(z.k_slide_no_fault <= 1.1 * slide_armed);
    }
}
