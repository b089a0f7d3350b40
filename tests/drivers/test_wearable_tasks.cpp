// test_wearable_tasks.cpp — seed 003's step, bandwidth and curvature experiments on the simulated
// wearable platform (drivers/sim/wearable_tasks.hpp), against the seed's figures (§3.7: rise about
// 0.1 s, steady error < 2 %, bandwidth about 3.5 Hz; the issue asks for 20 %) and the model's own.
#include "drivers/servo_loop.hpp"
#include "drivers/sim/sim_wearable_device.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/servo_scene.hpp"
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
    // Without the shaping Table 1's motor is an order of magnitude faster (docs/wearable.md).
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

TEST_CASE("sim-wearable device: cable forces, a pose, and bad commands as faults with zero output") {
    using namespace contactlab::drivers;
    SimWearableDevice dev;
    CHECK(dev.capabilities().platform);
    CHECK(dev.capabilities().force_sensors == 3);
    REQUIRE(dev.open());
    DeviceCommand cmd;
    cmd.platform_mode = DeviceCommand::PlatformMode::wrench;
    cmd.platform = {0.3, 0.3, 0.3};
    for (int k = 0; k < 500; ++k) {  // 0.5 s at 1 kHz
        dev.write(cmd);
        dev.advance(1e-3);
    }
    DeviceReading r;
    REQUIRE(dev.read(r));
    CHECK(r.valid);
    const IkResult ik = inverse_kinematics(dev.rig()->def().plant.platform, dev.rig()->plant().pose());
    for (int i = 0; i < 3; ++i) {
        // eq. 7 at the true tension, within 4 sigma of the FSR noise and friction's dead band.
        CHECK(std::abs(r.sensors[i] - 0.3 * ik.cables[i].cos_theta) < 4 * 0.003 + 0.005);
    }
    CHECK(dev.state() == DeviceState::ready);
    // Above the stall force: a fault, zero references, the tension falls away.
    cmd.platform = {0.3, 2.0, 0.3};
    dev.write(cmd);
    CHECK(dev.state() == DeviceState::fault);
    CHECK(dev.fault().code == DeviceFaultCode::over_limit);
    dev.advance(0.3);
    CHECK(dev.rig()->plant().tension().maxCoeff() < 0.01);
    // NaN: a fault, and a good command clears it.
    cmd.platform = {0.1, std::nan(""), 0.1};
    dev.write(cmd);
    CHECK(dev.fault().code == DeviceFaultCode::non_finite_command);
    cmd.platform_mode = DeviceCommand::PlatformMode::pose;
    cmd.platform = {0.0005, 0.05, 0.0};  // 0.5 mm into the pad, 0.05 rad of roll
    for (int k = 0; k < 600; ++k) {
        dev.write(cmd);
        dev.advance(1e-3);
    }
    CHECK(dev.state() == DeviceState::ready);
    CHECK(dev.rig()->plant().pose()(3) == doctest::Approx(0.05).epsilon(0.3));
    cmd.platform = {-0.02, 0.0, 0.0};  // 2 cm below the pad: no pose
    dev.write(cmd);
    CHECK(dev.fault().code == DeviceFaultCode::over_limit);
    // Silence: the watchdog zeroes the references.
    cmd.platform_mode = DeviceCommand::PlatformMode::wrench;
    cmd.platform = {0.2, 0.2, 0.2};
    dev.write(cmd);
    dev.advance(0.2);
    CHECK(dev.fault().code == DeviceFaultCode::watchdog);
    CHECK(dev.rig()->force_reference().isZero());
}

TEST_CASE("sim-wearable under the servo: a tilted finger on a flat floor tilts the platform by -phi and presses") {
    using namespace contactlab;
    using namespace contactlab::drivers;
    // The finger (R 2.6 cm) comes down 1.5 mm into scenes/flat.json's floor, then tilts by 0.2 rad;
    // the wearable pushes no hand, so the finger stays on its path.
    const HandPath path({PathSample{0.0, Vec2{0.0, 0.036}, 0.0}, PathSample{0.3, Vec2{0.0, 0.0245}, 0.0},
                         PathSample{0.8, Vec2{0.0, 0.0245}, 0.0}, PathSample{1.3, Vec2{0.0, 0.0245}, 0.2},
                         PathSample{2.0, Vec2{0.0, 0.0245}, 0.2}});
    SimWearableDevice dev(SimWearableParams{}, path);
    Scene scene = load_scene_file(std::string(CONTACTLAB_SOURCE_DIR) + "/scenes/flat.json");
    ServoParams params;
    params.stiffness = scene.force.stiffness;
    params.max_force = scene.force.max_force;
    ServoTick tick(servo_config_for(dev, 1000.0), params);
    tick.scenes().publish(std::make_unique<ServoScene>(scene));
    ServoLoop loop(dev, tick, 1e-3, nullptr);
    REQUIRE(loop.start());
    loop.run_virtual(2000);
    REQUIRE(dev.rig() != nullptr);
    const Pose& xi = dev.rig()->plant().pose();
    const Pose& rest = dev.rig()->def().plant.platform.rest;
    MESSAGE("roll " << xi(3) << " rad, press " << (xi(2) - rest(2)) << " m, state " << std::string(to_string(dev.state())));
    CHECK(dev.state() != DeviceState::fault);
    // The floor seen from the pad slopes down toward the fingertip by phi: roll -0.2 rad, within
    // the position loop's friction band and the FSR noise (as the curvature task: ~0.01 rad rms).
    CHECK(xi(3) == doctest::Approx(-0.2).epsilon(0.15));
    // |F| = 1.5 N (the scene's clamp) pressed as 1.5 N / 2 N/mm = 0.75 mm.
    CHECK(xi(2) - rest(2) == doctest::Approx(0.00075).epsilon(0.2));
}
