// Roller tracking on seed 000's block task (seed 001: max error 0.05 mm at 5 cm/s, about 0.01 mm
// for slow motion), the same closed loop at 1 and 4 kHz (continuous-time gains), and the 1 cm sine
// bandwidth (seed 000: about 8 Hz).
#include "sim_fixture.hpp"

#include "drivers/sim/bench_probes.hpp"
#include "drivers/sim/roller_sine.hpp"
#include "haptics/scene_io.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

using namespace contactlab;
using namespace contactlab::test;
// The block-task run, the onset floor and the bandwidth are library code (drivers/sim/bench_probes.hpp),
// shared with `contactlab bench`: the numbers checked here are the ones the bench reports.
using drivers::sim::onset_floor;
using Tracking = drivers::sim::BlockTracking;

namespace {

Tracking block_task(double speed, double rate = 1000.0, const RollerGains& gains = RollerGains{}) {
    const Tracking tr = drivers::sim::block_task_tracking(speed, rate, gains);
    REQUIRE(tr.opened);
    return tr;
}

constexpr double kAngleCount = 0.026 * 2.0 * 3.141592653589793 / 4096.0;  // m: R 2 pi / 4096

}  // namespace

TEST_CASE("the built-in block scene is scenes/block.json") {
    // The probes build the block in code (no scene file at run time); the tests used the file.
    CHECK(scene_to_json_text(drivers::block_scene()) == scene_to_json_text(load_shipped_scene("block.json")));
}

TEST_CASE("roller tracks the contact location on the block task at 5 cm/s and 1 cm/s") {
    const Tracking fast = block_task(0.05);
    const Tracking slow = block_task(0.01);
    const double floor_fast = onset_floor(fast.max_rate, 1e-3), floor_slow = onset_floor(slow.max_rate, 1e-3);
    std::printf("roller tracking, block task, 1 kHz: 5 cm/s max error %.4f mm (element %.4f mm, l_d up to %.1f mm/s, "
                "onset floor %.4f mm), 1 cm/s %.4f mm (element %.4f mm, floor %.4f mm + one angle count %.4f mm); "
                "l_d range %.2f mm\n",
                fast.max_measured * 1e3, fast.max_element * 1e3, fast.max_rate * 1e3, floor_fast * 1e3,
                slow.max_measured * 1e3, slow.max_element * 1e3, floor_slow * 1e3, kAngleCount * 1e3,
                fast.l_range * 1e3);
    // The task must actually move the roller (the contact runs back along the pad at the edge).
    CHECK(fast.l_range > 0.004);
    // Past the edge l_d starts along the pad at about the hand speed from rest: a target stepping
    // to that speed cannot be tracked better than onset_floor() (0.13-0.16 mm at 5-6 cm/s with this
    // motor, so seed 001's 0.05 mm is out of reach for this onset; l_d ramps up over a few ms, so
    // the PID may do slightly better). The PID must stay within 1.5x of that floor; slow
    // motion adds one count of the angle encoder (l_d = -R phi steps by R 2 pi / 4096 = 0.04 mm).
    CHECK(fast.max_measured < 1.5 * floor_fast);
    CHECK(slow.max_measured < 1.5 * (floor_slow + kAngleCount));
}

TEST_CASE("continuous-time roller gains: the block task tracks alike at 1, 4 and 10 kHz") {
    const Tracking k1 = block_task(0.05, 1000.0);
    // A sampled loop lags its continuous twin by about one period (half from the zero-order hold
    // on the drive, half from the backward-difference rate), so on a target moving at v two rates
    // may differ by v (T_a - T_b), e.g. 0.75 ms x v for 1 and 4 kHz; more would be the
    // discretisation. (It holds while the closed-loop poles, 400 rad/s, stay well inside the
    // sampling: p T <= 0.4, i.e. from 1 kHz up; docs/simulation.md gives the lower rates.)
    for (double rate : {4000.0, 10000.0}) {
        const Tracking kn = block_task(0.05, rate);
        const double v = std::max(k1.max_rate, kn.max_rate);   // m/s
        const double tol = v * (1.0 / 1000.0 - 1.0 / rate);     // m
        std::printf("roller tracking, block task, 5 cm/s: 1 kHz %.4f mm, %.0f kHz %.4f mm (tolerance %.4f mm at %.1f mm/s)\n",
                    k1.max_measured * 1e3, rate / 1000.0, kn.max_measured * 1e3, tol * 1e3, v * 1e3);
        CHECK(std::abs(k1.max_measured - kn.max_measured) <= tol);
    }
    // The same gains applied per tick instead (Ki T and Kd / T frozen at their 1 kHz values, i.e.
    // at 4 kHz the integral 4x slower and the damping 4x stronger) are not the same loop: the
    // check above is not vacuous.
    const double tol4 = std::max(k1.max_rate, 0.05) * (1.0 / 1000.0 - 1.0 / 4000.0);  // m
    RollerGains per_tick;
    per_tick.ki /= 4.0;
    per_tick.kd *= 4.0;
    const Tracking naive = block_task(0.05, 4000.0, per_tick);
    std::printf("roller tracking, block task, 5 cm/s, 4 kHz with per-tick gains frozen at 1 kHz: %.4f mm\n",
                naive.max_measured * 1e3);
    CHECK(std::abs(k1.max_measured - naive.max_measured) > tol4);
}

TEST_CASE("1 cm sine bandwidth of the simulated CLD roller at 1 kHz (seed 000: about 8 Hz)") {
    const drivers::sim::RollerParams p;
    const drivers::sim::SineTest st;  // 1 kHz, 5 mm amplitude = 1.0 cm peak to peak (what roller_bandwidth_hz runs)
    const double bandwidth = roller_bandwidth_hz(false);  // Hz
    REQUIRE(std::isfinite(bandwidth));
    // Physics band. The sine A sin(w t) asks the nut for m A w^2 + c A w (inertia, back-EMF) in
    // quadrature, plus sliding friction; the motor has the stall force at most. Below f_sat, where
    // the demand first reaches it, the loop is linear and tracks (gain ~1); even a full-force
    // square wave on the bare mass (no damping: an upper bound) gives a fundamental of
    // (4 F / pi) / (m w^2), which falls to A / sqrt 2 at f_bb. So f_sat <= f_-3dB <= f_bb.
    const double n = 2.0 * 3.141592653589793 / p.lead;                        // rad/m
    const double m = p.rotor_inertia * n * n + p.nut_mass;                    // kg
    const double c = std::pow(p.torque_constant * n, 2) / p.resistance + p.viscous;  // N s/m
    const double f_net = p.torque_constant * n * p.max_voltage / p.resistance - p.coulomb;  // N
    const double A = st.amplitude;
    double lo = 0.1, hi = 1000.0;  // rad/s: bisection for A w sqrt((m w)^2 + c^2) = f_net
    for (int i = 0; i < 100; ++i) {
        const double w = 0.5 * (lo + hi);
        (A * w * std::hypot(m * w, c) > f_net ? hi : lo) = w;
    }
    const double f_sat = lo / (2.0 * 3.141592653589793);
    const double f_bb = std::sqrt(4.0 * std::sqrt(2.0) * f_net / (3.141592653589793 * m * A)) / (2.0 * 3.141592653589793);
    std::printf("roller 1 cm p-p sine bandwidth at 1 kHz: %.2f Hz (saturation from %.2f Hz, bang-bang bound %.2f Hz; "
                "seed 000: about 8 Hz)\n", bandwidth, f_sat, f_bb);
    CHECK(bandwidth >= f_sat);
    CHECK(bandwidth <= f_bb);
    // Seed band. "Approximately 8 Hz" is one significant figure: 7.5..8.5 Hz. Seed 000 says
    // "1.0 cm sinusoidal commands" without saying peak to peak (used here: 2 x 5 mm fits the 20 mm
    // travel) or amplitude; were it the amplitude, a force-limited roller (f ~ A^-1/2 for the
    // inertia-limited part, which the bounds above show dominates) would reach sqrt 2 times higher
    // at our half amplitude: 8.5 sqrt 2 = 12.0 Hz.
    CHECK(bandwidth >= 7.5);
    CHECK(bandwidth <= 8.5 * std::sqrt(2.0));
    // Well inside the band the roller tracks: at 2 Hz within 1% in gain.
    const drivers::sim::SineResponse r2 = drivers::sim::roller_sine_response(p, RollerGains{}, st, 2.0);
    CHECK(std::abs(r2.gain - 1.0) < 0.01);
    // The bench's quick figure: a shorter sweep and a coarser bisection around the same crossing.
    // Both are midpoints of brackets that hold it, half-widths 0.025 and 0.005 Hz.
    const double quick = roller_bandwidth_hz(true);  // Hz
    std::printf("roller 1 cm p-p sine bandwidth, quick: %.2f Hz\n", quick);
    CHECK(std::abs(quick - bandwidth) <= 0.03 + 1e-9);
}

TEST_CASE("roller tracking error grows with finger speed at every gain scale") {
    // The block task's error is set by how l_d starts moving (past the edge it starts along the pad
    // at about the hand speed, from rest: onset_floor() grows as v T + v^2 / (2 a_max)) on top of a
    // speed-independent part (the angle encoder's 0.04 mm steps of l_d = -R phi exciting the loop).
    auto print = [](const char* what, const std::vector<RollerTrackingRow>& rows) {
        std::printf("roller tracking table (%s), block task, 1 kHz:\n| gain scale | pole (rad/s) | speed (m/s) | max (mm) | rms (mm) | element max (mm) | onset floor (mm) |\n", what);
        for (const RollerTrackingRow& r : rows)
            std::printf("| %.1f | %.0f | %.3f | %.4f | %.4f | %.4f | %.4f |\n", r.gain_scale, r.pole_rad_s, r.finger_speed,
                        r.max_error * 1e3, r.rms_error * 1e3, r.max_element_error * 1e3, r.onset_floor * 1e3);
    };
    // Rows come per gain scale, speeds ascending: the same-scale neighbour is the next row.
    // (The last group is gain scale 1 without the feed-forward: seed 000's eq. 2 alone.)
    auto same_scale = [](const RollerTrackingRow& a, const RollerTrackingRow& b) {
        return a.gain_scale == b.gain_scale && a.feed_forward == b.feed_forward;
    };

    const std::vector<RollerTrackingRow> quick = roller_tracking_table(true);
    print("quick", quick);
    REQUIRE(quick.size() == 6);
    for (std::size_t i = 0; i + 1 < quick.size(); ++i) {
        if (!same_scale(quick[i], quick[i + 1])) continue;
        INFO("gain scale " << quick[i].gain_scale << ", " << quick[i].finger_speed << " -> " << quick[i + 1].finger_speed << " m/s");
        REQUIRE(quick[i + 1].finger_speed > quick[i].finger_speed);
        CHECK(quick[i + 1].max_error > quick[i].max_error);
        CHECK(quick[i + 1].rms_error > quick[i].rms_error);
    }

    const std::vector<RollerTrackingRow> full = roller_tracking_table(false);
    print("full", full);
    REQUIRE(full.size() == 16);
    for (std::size_t i = 0; i + 1 < full.size(); ++i) {
        if (!same_scale(full[i], full[i + 1])) continue;
        INFO("gain scale " << full[i].gain_scale << ", " << full[i].finger_speed << " -> " << full[i + 1].finger_speed << " m/s");
        REQUIRE(full[i + 1].finger_speed > full[i].finger_speed);
        // RMS grows step by step at every scale. So does the maximum at the default gains and
        // below; at 2x (poles at 800 rad/s, p T = 0.8 at 1 kHz: a lightly damped sampled loop)
        // the encoder steps ring it, and at 1 cm/s the steps come at a spacing that rings it
        // harder than at 2 cm/s: there the maximum is only checked end to end, below.
        CHECK(full[i + 1].rms_error > full[i].rms_error);
        if (full[i].gain_scale <= 1.0) CHECK(full[i + 1].max_error > full[i].max_error);
    }
    for (std::size_t i = 0; i < full.size(); i += 4) {
        INFO("gain scale " << full[i].gain_scale);
        CHECK(full[i + 3].max_error > full[i].max_error);  // 10 cm/s against 1 cm/s
        // Fast motion sits near the actuator's onset floor whatever the gains: within 1.5x of it
        // (the bound the 5 cm/s test above uses), and no gain can beat it by much (l_d ramps up
        // over a few ms rather than stepping, so the PID may do slightly better than the floor).
        CHECK(full[i + 3].max_error < 1.5 * full[i + 3].onset_floor);
        CHECK(full[i + 3].max_error > 0.5 * full[i + 3].onset_floor);
    }
}

namespace {

// The roller alone tracking l_d = l0 + v t from rest (no encoder steps in the target), at 1 kHz:
// the largest |l_d - l| after `skip` s (the onset's transient).
double ramp_error(const RollerGains& g, double v, double skip) {
    const drivers::sim::RollerParams p;
    drivers::sim::CldRoller roller(p);
    const double l0 = -0.008;  // m: 16 mm of room at 5 cm/s is 0.32 s
    roller.place_at(l0);
    RollerController ctl(g, RollerTravel{-roller.half_travel(), roller.half_travel()});
    ctl.reset(roller.measured());
    const double T = 1e-3;  // s
    double worst = 0.0;     // m
    for (int k = 0; k < 300; ++k) {
        const double target = l0 + v * k * T;  // m
        const double l = roller.measured();    // m
        roller.set_voltage(ctl.step(target, l, T));
        if (k * T >= skip) worst = std::max(worst, std::abs(target - l));
        for (int i = 0; i < 10; ++i) roller.step(T / 10);
    }
    return worst;
}

}  // namespace

TEST_CASE("a ramp of l_d: eq. 2 alone lags by what the rail leaves to P, the velocity feed-forward does not") {
    const drivers::sim::RollerParams p;
    const RollerGains ff;  // defaults: kff = Kd + back-EMF
    RollerGains pure = ff;
    pure.kff = 0.0;
    const double v = 0.05;  // m/s, seed 001's fast hand speed
    // Eq. 2 damps the measured rate: moving at v takes (Kd + back_emf) v of drive plus the
    // friction's, and anti-windup keeps the integral within the 12 V rail, so P must hold the rest.
    const double volts_per_newton = p.resistance / (p.torque_constant * 2.0 * 3.141592653589793 / p.lead);  // V/N
    const double need = (pure.kd + pure.back_emf) * v + p.coulomb * volts_per_newton;  // V
    const double lag = (need - pure.max_drive) / pure.kp;                              // m
    const double off = ramp_error(pure, v, 0.05), on = ramp_error(ff, v, 0.05);
    std::printf("roller alone, 5 cm/s ramp after 50 ms: eq. 2 %.4f mm (predicted lag %.4f mm), with feed-forward %.4f mm\n",
                off * 1e3, lag * 1e3, on * 1e3);
    CHECK(off == doctest::Approx(lag).epsilon(0.1));
    // With the drive paid in advance nothing is left for P to hold but friction's 0.2 V (0.6 um)
    // and the encoder's 0.17 um counts; 5 um leaves room for the stiction's stick-slip.
    CHECK(on < 5e-6);
    CHECK(sampled_roller_gains(ff, 1e-3).kff == ff.kff);
    // Below 1 kHz the feed-forward is re-placed with Kd (it must keep cancelling Kd + back-EMF).
    const RollerGains g250 = sampled_roller_gains(ff, 4e-3);
    CHECK(g250.kff == doctest::Approx(g250.kd + g250.back_emf).epsilon(1e-9));
}

TEST_CASE("block task: tracking during motion (seed 001: 0.05 mm at 5 cm/s), jumps of l_d apart") {
    RollerGains pure;
    pure.kff = 0.0;
    const Tracking on = block_task(0.05), off = block_task(0.05, 1000.0, pure);
    std::printf("block task, 5 cm/s, 1 kHz: tracking max %.4f mm (eq. 2 alone %.4f mm), jumps %d (max %.4f mm), all %.4f mm\n",
                on.max_tracking * 1e3, off.max_tracking * 1e3, on.jumps, on.max_jump * 1e3, on.max_measured * 1e3);
    // The jumps are found: the corner's onset, the stop when the finger tips, contact made and lost.
    CHECK(on.jumps >= 3);
    CHECK(on.jumps == off.jumps);  // found on l_d, which the roller does not change
    CHECK(on.tracking_samples > on.samples / 2);
    // Eq. 2 alone lags the ramp past the corner (at the task's ~54 mm/s, (Kd + back-EMF) v - 12 V
    // held by P: ~0.1 mm); with the feed-forward what is left is l_d's own encoder steps.
    CHECK(off.max_tracking > 0.08e-3);
    CHECK(on.max_tracking <= 0.05e-3);
    // The jumps keep the error the motor's force sets (onset_floor), not less.
    CHECK(on.max_jump > 0.5 * onset_floor(on.max_rate, 1e-3));
}

TEST_CASE("a jump of l_d settles within the force-limited time's reach and stays inside the travel") {
    const std::vector<RollerJumpRow> rows = roller_jump_table(false);
    REQUIRE(rows.size() == 3);
    for (const RollerJumpRow& r : rows) {
        std::printf("roller jump %.1f mm at 1 kHz: settles into %.3f mm in %.1f ms (force-limited %.1f ms), overshoot "
                    "%.3f mm, furthest %.2f of %.1f mm\n", r.jump * 1e3, r.band * 1e3, r.jump_settle_s * 1e3,
                    r.force_limited_s * 1e3, r.overshoot * 1e3, r.max_excursion * 1e3, r.half_travel * 1e3);
        CAPTURE(r.jump);
        // Nothing beats full drive then full reverse; the PID's linear tail (400 rad/s triple
        // pole: ~20 ms to 0.05 mm) comes on top: within 2x and 30 ms of it.
        CHECK(r.jump_settle_s >= r.force_limited_s);
        CHECK(r.jump_settle_s <= std::min(2.0 * r.force_limited_s, r.force_limited_s + 0.030));
        // Never past the travel (the 16 mm jump ends 2 mm from the stop), and under 1 mm past the target.
        CHECK(r.max_excursion < r.half_travel);
        CHECK(r.overshoot < 1e-3);
    }
}

TEST_CASE("block task against the true contact location: the encoders' staircase, and what the finger feels") {
    const double R = 0.026;                      // m, the block scene's finger
    const drivers::sim::SimCldParams rig;        // the rig block_task() runs
    const double pi = 3.141592653589793;
    // The staircase |l_d(encoders) - l_d(true)|. The angle encoder rounds phi to a count, so l_d
    // (R times an angle on the pad) is off by at most half a count, R pi / 4096 = 0.020 mm. The
    // arm's joints round by half a count each, pi / 65536 rad: the endpoint moves by at most
    // (|base - endpoint| + l2) times that, under (l1 + 2 l2) pi / 65536 = 0.029 mm; at the corner
    // l_d turns with the finger's direction from it, |x_f - corner| >= R - d (d <= 1.5 N / 1000 N/m
    // = 1.5 mm, the clamp's depth), so R / (R - d) times that reaches l_d. On the top only phi counts.
    const double half_angle = 0.5 * kAngleCount;                                                   // m
    const double arm = (rig.arm.l1 + 2.0 * rig.arm.l2) * pi / rig.arm.encoder_counts * R / (R - 0.0015);  // m
    for (double speed : {0.01, 0.05}) {
        const Tracking tr = block_task(speed);
        std::printf("block task, %.0f cm/s, 1 kHz, tracking ticks: vs l_d from encoders %.4f mm; vs true l_d: element "
                    "%.4f mm (RMS %.4f mm), encoder %.4f mm; staircase %.4f mm (bound %.4f + %.4f mm); wires %.4f mm\n",
                    speed * 100.0, tr.max_tracking * 1e3, tr.max_true_tracking * 1e3, tr.rms_true_tracking * 1e3,
                    tr.max_true_encoder * 1e3, tr.max_staircase * 1e3, half_angle * 1e3, arm * 1e3, tr.max_wire * 1e3);
        CAPTURE(speed);
        // The true proxy is in contact on (nearly) every tracking tick: contact is made and lost
        // inside the jumps' windows, whatever the encoders say.
        CHECK(tr.true_samples >= tr.tracking_samples * 99 / 100);
        CHECK(tr.max_staircase <= half_angle + arm);
        // Over thousands of angle counts the rounding error sweeps all of +-half a count: the
        // reference really is unquantised.
        CHECK(tr.max_staircase >= 0.9 * half_angle);
        // Tick by tick true - element = (true - target) + (target - encoder) + (encoder - element).
        CHECK(tr.max_true_encoder <= tr.max_staircase + tr.max_tracking + 1e-12);
        CHECK(tr.max_true_tracking <= tr.max_true_encoder + tr.max_wire + 1e-12);
        // A staircase of +-0.02 mm or more: no roller is within 0.01 mm of the true l_d and of
        // the servo's target at once; this one is nearer neither (seed 001's slow 0.01 mm is not met).
        CHECK(tr.max_true_tracking > 0.01e-3);
    }

    // The same task with encoders of 2^30 counts (half a count moves l_d by under 2e-9 m): the two proxies
    // are the same code on the same history, so the staircase vanishes; what is left is the
    // loop's own error. At 1 cm/s it is still over 0.01 mm, at the corner: past the edge l_d's rate
    // steps from 0 to ~12 mm/s (the contact leaves the top for the corner), which no controller
    // that learns of it a period late and accelerates at the stall force follows better than
    // onset_floor() = v T + v^2 / (2 a_max) = 0.016 mm. Seed 001's 0.01 mm is therefore out of
    // reach on this task at 1 cm/s whatever the sensing, target filter or feed-forward.
    drivers::sim::SimCldParams ideal;
    ideal.angle_encoder_counts = 1 << 30;
    ideal.arm.encoder_counts = 1 << 30;
    const Tracking fine = drivers::sim::block_task_tracking(0.01, 1000.0, RollerGains{}, 0.0, ideal);
    REQUIRE(fine.opened);
    const double floor = onset_floor(fine.max_rate, 1e-3);  // m
    std::printf("block task, 1 cm/s, ideal encoders: staircase %.2e mm, vs true l_d: encoder %.4f mm, element %.4f mm "
                "(RMS %.4f mm); onset floor %.4f mm at %.1f mm/s\n", fine.max_staircase * 1e3, fine.max_true_encoder * 1e3,
                fine.max_true_tracking * 1e3, fine.rms_true_tracking * 1e3, floor * 1e3, fine.max_rate * 1e3);
    CHECK(fine.max_staircase < 1e-8);
    CHECK(floor > 0.01e-3);
    // The measured error sits at the floor (the kink is smoothed a little by the finger's own
    // dynamics, so the PID may come slightly under it) and under the 1.5x the tests above allow.
    CHECK(fine.max_true_encoder > 0.75 * floor);
    CHECK(fine.max_true_encoder < 1.5 * floor);
}
