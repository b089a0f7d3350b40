// Roller tracking on seed 000's block task (seed 001: max error 0.05 mm at 5 cm/s, about 0.01 mm
// for slow motion), the same closed loop at 1 and 4 kHz (continuous-time gains), and the 1 cm sine
// bandwidth (seed 000: about 8 Hz).
#include "sim_fixture.hpp"

#include "drivers/sim/roller_sine.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <deque>

using namespace contactlab;
using namespace contactlab::test;

namespace {

struct Tracking {
    double max_measured = 0.0;  // m, |l_target - l_encoder|
    double max_element = 0.0;   // m, |l_target - l_element| (what the finger feels)
    double l_range = 0.0;       // m, how far l_d travelled
    double max_rate = 0.0;      // m/s, fastest l_d over 10 ms windows (encoder steps averaged out)
};

Tracking block_task(double speed, double rate = 1000.0, const RollerGains& gains = RollerGains{}) {
    drivers::BlockTaskParams bp;
    bp.speed = speed;
    ServoParams params;
    params.roller = gains;
    SimRig rig(load_shipped_scene("block.json"), drivers::contour_block_task(bp), rate, {}, params);
    REQUIRE(rig.opened);
    Tracking tr;
    double lmin = 1e9, lmax = -1e9;
    const double T = 1.0 / rate;  // s
    const auto window = static_cast<std::size_t>(std::lround(0.010 * rate));
    std::deque<double> recent;    // m, the last `window` targets while engaged in contact
    const auto ticks = static_cast<std::uint64_t>(std::lround(rig.device.hand().path().end() * rate));
    for (std::uint64_t k = 0; k < ticks; ++k) {
        rig.loop.step(T, true);
        const ServoSnapshot s = rig.servo.snapshot();
        if (s.state != ServoState::engaged || !s.contact) {
            recent.clear();
            continue;
        }
        lmin = std::min(lmin, s.roller_target);
        lmax = std::max(lmax, s.roller_target);
        tr.max_measured = std::max(tr.max_measured, std::abs(s.roller_target - s.roller_l));
        tr.max_element = std::max(tr.max_element, std::abs(s.roller_target - rig.device.roller().element()));
        recent.push_back(s.roller_target);
        if (recent.size() > window) {
            recent.pop_front();
            tr.max_rate = std::max(tr.max_rate, std::abs(recent.back() - recent.front()) / (window - 1) * rate);
        }
    }
    tr.l_range = lmax - lmin;
    return tr;
}

// The least error any controller can have on a target that starts moving at v (m/s) from rest,
// with the roller at rest: it learns of the motion up to one period T (s) late, and then needs
// v / a_max to reach v, falling behind by v^2 / (2 a_max). a_max (m/s^2) is the stall force less
// sliding friction over the mass reflected to the nut.
double onset_floor(double v, double T) {
    const drivers::sim::RollerParams p;
    const double n = 2.0 * 3.141592653589793 / p.lead;                  // rad/m
    const double mass = p.rotor_inertia * n * n + p.nut_mass;           // kg
    const double stall = p.torque_constant * n * p.max_voltage / p.resistance;  // N
    const double a_max = (stall - p.coulomb) / mass;                    // m/s^2
    return v * T + v * v / (2.0 * a_max);
}

constexpr double kAngleCount = 0.026 * 2.0 * 3.141592653589793 / 4096.0;  // m: R 2 pi / 4096

}  // namespace

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
    // sampling: p T <= 0.4, i.e. from 1 kHz up; README "Simulation" gives the lower rates.)
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
    drivers::sim::SineTest st;  // 1 kHz, 5 mm amplitude = 1.0 cm peak to peak
    const drivers::sim::BandwidthResult bw = drivers::sim::roller_bandwidth(p, RollerGains{}, st);
    REQUIRE(bw.found);
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
                "seed 000: about 8 Hz)\n", bw.bandwidth, f_sat, f_bb);
    CHECK(bw.bandwidth >= f_sat);
    CHECK(bw.bandwidth <= f_bb);
    // Seed band. "Approximately 8 Hz" is one significant figure: 7.5..8.5 Hz. Seed 000 says
    // "1.0 cm sinusoidal commands" without saying peak to peak (used here: 2 x 5 mm fits the 20 mm
    // travel) or amplitude; were it the amplitude, a force-limited roller (f ~ A^-1/2 for the
    // inertia-limited part, which the bounds above show dominates) would reach sqrt 2 times higher
    // at our half amplitude: 8.5 sqrt 2 = 12.0 Hz.
    CHECK(bw.bandwidth >= 7.5);
    CHECK(bw.bandwidth <= 8.5 * std::sqrt(2.0));
    // Well inside the band the roller tracks: at 2 Hz within 1% in gain.
    const drivers::sim::SineResponse r2 = drivers::sim::roller_sine_response(p, RollerGains{}, st, 2.0);
    CHECK(std::abs(r2.gain - 1.0) < 0.01);
}
