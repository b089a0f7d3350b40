// test_wearable_tasks.cpp — seed 003's step, bandwidth and curvature experiments on the simulated
// wearable platform (drivers/sim/wearable_tasks.hpp), against the seed's figures (§3.7: rise about
// 0.1 s, steady error < 2 %, bandwidth about 3.5 Hz; the issue asks for 20 %) and the model's own.
#include "drivers/sim/wearable_tasks.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace contactlab::drivers::sim;
using namespace contactlab::wearable;

namespace {
RigDef noisy(RigDef def) {
    def.plant.fsr_noise = 0.003;  // N
    def.plant.noise_seed = 3;
    return def;
}
}  // namespace

TEST_CASE("wearable-step: the seed-fit rig rises in 0.1 s within 20 %, steady error under 2 %") {
    const WearableStepResult r = wearable_step(noisy(seed_fit_rig()));
    MESSAGE("rise " << r.rise_time_s << " s, steady error " << r.steady_error_pct << " %, overshoot " << r.overshoot_pct << " %");
    CHECK_FALSE(r.fault);
    CHECK(r.rise_time_s == doctest::Approx(0.1).epsilon(0.2));
    CHECK(r.steady_error_pct < 2.0);
    // The reference shaping is first order: 10-90 % in ln(9) tau = 0.0999 s, one 1 ms sample and
    // one 10 ms link tick of slack.
    const RigDef fit = seed_fit_rig();
    CHECK(std::abs(r.rise_time_s - std::log(9.0) * fit.reference_time_constant) < 0.012);
    // Without the shaping Table 1's motor is an order of magnitude faster (README, issue 17).
    const WearableStepResult raw = wearable_step(RigDef{});
    CHECK(raw.rise_time_s < 0.02);
    CHECK(raw.steady_error_pct < 2.0);
}

TEST_CASE("wearable-bandwidth: the seed's 0.5 Hz sine is tracked, -3 dB near 3.5 Hz") {
    const RigDef def = seed_fit_rig();
    std::vector<WearableSample> run;
    const WearableSineResponse slow = wearable_sine(def, WearableSineDef{}, 0.5, &run);
    // A first-order 45 ms shaping at 0.5 Hz: gain 1 / sqrt(1 + (2 pi 0.5 tau)^2) = 0.990.
    CHECK(slow.gain == doctest::Approx(0.990).epsilon(0.01));
    CHECK_FALSE(run.empty());
    for (const WearableSample& s : run) CHECK(s.estimate.allFinite());
    // The gain at 3.5 Hz is 1 / sqrt(2) for the shaping alone; the 100 Hz link's hold adds ~5 ms of lag.
    const WearableSineResponse at = wearable_sine(def, WearableSineDef{}, 3.5);
    CHECK(at.gain == doctest::Approx(1.0 / std::sqrt(2.0)).epsilon(0.2));
    CHECK(at.phase < -0.7);
}

TEST_CASE("curvature-arc: the platform tilts with the arc's slope on h = 10, 20, 30 mm") {
    const RigDef def = noisy(seed_fit_rig());
    for (const double h : {0.010, 0.020, 0.030}) {
        CurvatureArcDef cd;
        cd.height = h;
        const CurvatureArcResult r = curvature_arc(def, cd);
        MESSAGE("h " << h * 1e3 << " mm: tilt rms " << r.tilt_rms << " rad, max error " << r.tilt_max_error
                     << " rad, surface angle up to " << r.max_surface_angle << " rad");
        CHECK_FALSE(r.fault);
        CHECK(r.radius == doctest::Approx((0.25 * 0.09 + h * h) / (2.0 * h)).epsilon(1e-12));
        // Tracking to a tenth of the largest slope on the flattest arc (0.133 rad at h = 10 mm).
        CHECK(r.tilt_rms < 0.1 * 0.133);
        bool touched = false;
        for (const CurvatureSample& s : r.samples) {
            CHECK(std::isfinite(s.platform_tilt));
            if (s.contact) touched = true;
            if (!s.contact) CHECK(s.surface_angle == 0.0);
        }
        CHECK(touched);
    }
    CurvatureArcDef bad;
    bad.height = 0.2;  // more than half the 0.30 m chord
    CHECK_THROWS_AS(curvature_arc(def, bad), std::invalid_argument);
}
